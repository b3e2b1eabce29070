// The support graph as the editor sees it: the saved supports with unsaved edits on top.
import type {
  RemoveSupport,
  RestoreSupport,
  SceneObject,
  SetSupport,
  SupportRelation,
} from "@holiscene/schema";
import { STRUCTURAL_SUPPORT_TYPES, STRUCTURAL_SUPPORTERS } from "@holiscene/schema";

// The generated types have `kind` optional (it has a default in pydantic); the app always
// sends it, and requiring it here lets TypeScript tell the kinds apart.
export type SetSupportEdit = SetSupport & { kind: "set_support" };
export type RemoveSupportEdit = RemoveSupport & { kind: "remove_support" };
/**
 * Back to the supporter an earlier revision stored (undo, revert). `restores` is that
 * supporter (null: none), kept by the app to show it; the server reads the revision itself.
 */
export type RestoreSupportEdit = RestoreSupport & {
  kind: "restore_support";
  restores: SupportRelation | null;
};
export type Edit = SetSupportEdit | RemoveSupportEdit | RestoreSupportEdit;
export type SupportType = SupportRelation["type"];
export type StructuralSupporter = (typeof STRUCTURAL_SUPPORTERS)[number];
export type SupportSource = SupportRelation["source"];

export function isStructural(parent: string): parent is StructuralSupporter {
  return (STRUCTURAL_SUPPORTERS as readonly string[]).includes(parent);
}

/** The objects (room parts aside) that have no supporter among `shown`. */
export function withoutSupporter<T extends { id: string; class: string }>(
  objects: readonly T[],
  shown: ReadonlyMap<string, unknown>,
): T[] {
  return objects.filter((o) => !isStructural(o.class) && !shown.has(o.id));
}

/** An object's supporter as shown: saved, or changed by an edit not yet saved. */
export interface ShownSupport {
  child: string;
  parent: string;
  type: SupportType;
  /** The saved relation when nothing unsaved changes it; null otherwise. */
  saved: SupportRelation | null;
  pending: boolean;
  /** Provenance: a person's (manual) or the pipeline's guess (auto); unsaved sets are manual. */
  source: SupportSource;
  author: string | null;
  time: string | null;
  confidence: number | null;
}

/** An edit as the server takes it (without what the app keeps beside it). */
export function wireEdit(edit: Edit): SetSupport | RemoveSupport | RestoreSupport {
  if (edit.kind !== "restore_support") return edit;
  return { kind: edit.kind, child: edit.child, from_revision: edit.from_revision };
}

function fromRelation(relation: SupportRelation, pending: boolean): ShownSupport {
  return {
    child: relation.child,
    parent: relation.parent,
    type: relation.type,
    saved: pending ? null : relation,
    pending,
    source: relation.source,
    author: relation.author ?? null,
    time: relation.time ?? null,
    confidence: relation.confidence ?? null,
  };
}

/** child id -> its supporter, after applying the unsaved edits (in order). */
export function shownSupports(
  saved: readonly SupportRelation[],
  pending: Iterable<Edit>,
): Map<string, ShownSupport> {
  const shown = new Map<string, ShownSupport>();
  for (const relation of saved) shown.set(relation.child, fromRelation(relation, false));
  for (const edit of pending) {
    if (edit.kind === "remove_support") {
      shown.delete(edit.child);
    } else if (edit.kind === "restore_support") {
      if (edit.restores) shown.set(edit.child, fromRelation(edit.restores, true));
      else shown.delete(edit.child);
    } else {
      shown.set(edit.child, {
        child: edit.child,
        parent: edit.parent,
        type: edit.type,
        saved: null,
        pending: true,
        source: "manual",
        author: null,
        time: null,
        confidence: null,
      });
    }
  }
  return shown;
}

/** Whether two stored relations are the same, provenance included. */
export function sameRelation(
  a: SupportRelation | null | undefined,
  b: SupportRelation | null | undefined,
): boolean {
  if (!a || !b) return !a && !b;
  return (
    a.child === b.child &&
    a.parent === b.parent &&
    a.type === b.type &&
    a.source === b.source &&
    (a.author ?? null) === (b.author ?? null) &&
    (a.time ?? null) === (b.time ?? null) &&
    (a.confidence ?? null) === (b.confidence ?? null)
  );
}

/**
 * Whether `edit` would leave the child's supporter exactly as it is saved. Setting the
 * supporter a guess already names is not: it makes the guess a person's label (accepting).
 */
export function isNoOp(edit: Edit, saved: readonly SupportRelation[]): boolean {
  const current = saved.find((s) => s.child === edit.child);
  switch (edit.kind) {
    case "remove_support":
      return current === undefined;
    case "restore_support":
      return sameRelation(current, edit.restores);
    case "set_support":
      return (
        current !== undefined &&
        current.source === "manual" &&
        current.parent === edit.parent &&
        current.type === edit.type
      );
  }
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

/** The supporter an edit gives its child (null: none). */
function editParent(edit: Edit): string | null {
  if (edit.kind === "set_support") return edit.parent;
  if (edit.kind === "restore_support") return edit.restores?.parent ?? null;
  return null;
}

/** Why an edit cannot apply to these objects, or null when it can. */
export function editProblem(edit: Edit, objects: readonly SceneObject[]): string | null {
  const ids = new Set(objects.map((o) => o.id));
  if (!ids.has(edit.child)) return `object ${edit.child} no longer exists`;
  const parent = editParent(edit);
  if (parent !== null && !ids.has(parent) && !isStructural(parent)) {
    return `supporter ${parent} of ${edit.child} no longer exists`;
  }
  return null;
}

/** The usual support type for a supporter: walls and ceilings hold from behind (and only so),
 * the floor and objects from below. */
export function defaultType(parent: string): SupportType {
  return STRUCTURAL_SUPPORT_TYPES[parent] ?? "below";
}

/** The one type a part of the room holds objects up by; null for an object (either type). */
export const onlyType = (parent: string): SupportType | null =>
  STRUCTURAL_SUPPORT_TYPES[parent] ?? null;

/**
 * The type of an edge whose supporter becomes `parent`: a part of the room's own type; between
 * objects the current type, unless the supporter changes kind (a picture moved from a wall to
 * a shelf rests on it from below).
 */
export function typeFor(
  parent: string,
  current?: { parent: string; type: SupportType } | null,
): SupportType {
  const only = onlyType(parent);
  if (only) return only;
  return current && defaultType(current.parent) === defaultType(parent)
    ? current.type
    : defaultType(parent);
}

/** A readable description of an edit, for notices and the pending list. */
export function describeEdit(edit: Edit): string {
  switch (edit.kind) {
    case "remove_support":
      return `${edit.child}: no supporter`;
    case "set_support":
      return `${edit.child}: on ${edit.parent} (${edit.type})`;
    case "restore_support": {
      const r = edit.restores;
      return r
        ? `${edit.child}: back on ${r.parent} (${r.type}, ${r.source === "auto" ? "predicted" : `by ${r.author ?? "someone"}`})`
        : `${edit.child}: back to no supporter`;
    }
  }
}

/** Below this confidence the pipeline's supporter is more likely wrong than right: its arrow
 * is drawn faint, so a reviewer does not take a 42% guess (a wall clock "on" a chair) for a
 * settled support. */
export const DOUBTFUL_SUPPORT = 0.5;

/** Whether a stored support is the pipeline's guess at under even odds. */
export const isDoubtfulSupport = (support: ShownSupport | null | undefined): boolean =>
  support?.source === "auto" &&
  typeof support.confidence === "number" &&
  support.confidence < DOUBTFUL_SUPPORT;

/**
 * Why a supporter from below looks wrong on the photo (null: nothing to say): one object holds
 * up another from below only where it is under it, so the two boxes share some of their width.
 * A person who picked the wrong object on a crowded photo learns it here rather than in 3D.
 */
export function implausibleBelow(
  child: Pick<SceneObject, "id" | "bbox">,
  parent: Pick<SceneObject, "id" | "bbox"> | undefined,
  type: SupportType,
): string | null {
  if (!parent || type !== "below") return null;
  const [cx1, , cx2] = child.bbox;
  const [px1, , px2] = parent.bbox;
  if (Math.min(cx2, px2) > Math.max(cx1, px1)) return null;
  return `${parent.id} is beside ${child.id} on the photo, not under it: is it the right supporter?`;
}
