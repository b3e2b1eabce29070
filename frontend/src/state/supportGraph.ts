// The support graph as the editor sees it: the saved supports with unsaved edits on top.
import type { RemoveSupport, SceneObject, SetSupport, SupportRelation } from "@holiscene/schema";
import { STRUCTURAL_SUPPORTERS } from "@holiscene/schema";

// The generated types have `kind` optional (it has a default in pydantic); the app always
// sends it, and requiring it here lets TypeScript tell the two kinds apart.
export type SetSupportEdit = SetSupport & { kind: "set_support" };
export type RemoveSupportEdit = RemoveSupport & { kind: "remove_support" };
export type Edit = SetSupportEdit | RemoveSupportEdit;
export type SupportType = SupportRelation["type"];
export type StructuralSupporter = (typeof STRUCTURAL_SUPPORTERS)[number];

export function isStructural(parent: string): parent is StructuralSupporter {
  return (STRUCTURAL_SUPPORTERS as readonly string[]).includes(parent);
}

/** An object's supporter as shown: saved, or changed by an edit not yet saved. */
export interface ShownSupport {
  child: string;
  parent: string;
  type: SupportType;
  /** Absent for an unsaved edit. */
  saved: SupportRelation | null;
  pending: boolean;
}

/** child id -> its supporter, after applying the unsaved edits (in order). */
export function shownSupports(
  saved: readonly SupportRelation[],
  pending: Iterable<Edit>,
): Map<string, ShownSupport> {
  const shown = new Map<string, ShownSupport>();
  for (const relation of saved) {
    shown.set(relation.child, { ...relation, saved: relation, pending: false });
  }
  for (const edit of pending) {
    if (edit.kind === "remove_support") {
      shown.delete(edit.child);
    } else {
      shown.set(edit.child, {
        child: edit.child,
        parent: edit.parent,
        type: edit.type,
        saved: null,
        pending: true,
      });
    }
  }
  return shown;
}

/** Whether `edit` would leave the child's supporter exactly as it is saved. */
export function isNoOp(edit: Edit, saved: readonly SupportRelation[]): boolean {
  const current = saved.find((s) => s.child === edit.child);
  if (edit.kind === "remove_support") return current === undefined;
  return current !== undefined && current.parent === edit.parent && current.type === edit.type;
}

/** Whether making `parent` hold up `child` would close a loop (or is the child itself). */
export function wouldCycle(
  child: string,
  parent: string,
  supports: ReadonlyMap<string, { parent: string }>,
): boolean {
  const seen = new Set<string>();
  let node: string | undefined = parent;
  while (node !== undefined && !seen.has(node)) {
    if (node === child) return true;
    seen.add(node);
    node = supports.get(node)?.parent;
  }
  return false;
}

/** Why an edit cannot apply to these objects, or null when it can. */
export function editProblem(edit: Edit, objects: readonly SceneObject[]): string | null {
  const ids = new Set(objects.map((o) => o.id));
  if (!ids.has(edit.child)) return `object ${edit.child} no longer exists`;
  if (edit.kind === "set_support" && !ids.has(edit.parent) && !isStructural(edit.parent)) {
    return `supporter ${edit.parent} of ${edit.child} no longer exists`;
  }
  return null;
}

/** The usual support type for a supporter: walls and ceilings hold from behind. */
export function defaultType(parent: string): SupportType {
  return parent === "wall" || parent === "ceiling" ? "behind" : "below";
}

/** A readable description of an edit, for notices and the pending list. */
export function describeEdit(edit: Edit): string {
  return edit.kind === "remove_support"
    ? `${edit.child}: no supporter`
    : `${edit.child}: on ${edit.parent} (${edit.type})`;
}
