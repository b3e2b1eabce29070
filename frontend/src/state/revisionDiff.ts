// What changed between two revisions of a scene (the history's diff).
import type { Scene, SupportRelation } from "@holiscene/schema";
import { sameRelation } from "./supportGraph";

export type ChangeKind = "added" | "removed" | "moved" | "retyped" | "confirmed" | "provenance";

export interface SupportChange {
  child: string;
  kind: ChangeKind;
  before: SupportRelation | null;
  after: SupportRelation | null;
}

export interface SceneDiff {
  supports: SupportChange[];
  objectsAdded: string[];
  objectsRemoved: string[];
  layoutChanged: boolean;
}

function changeKind(before: SupportRelation | null, after: SupportRelation | null): ChangeKind {
  if (!before) return "added";
  if (!after) return "removed";
  if (before.parent !== after.parent) return "moved";
  if (before.type !== after.type) return "retyped";
  if (before.source === "auto" && after.source === "manual") return "confirmed";
  return "provenance";
}

/** The supports that differ (provenance included), in the objects' order. */
export function diffSupports(
  before: readonly SupportRelation[],
  after: readonly SupportRelation[],
): SupportChange[] {
  const old = new Map(before.map((s) => [s.child, s]));
  const now = new Map(after.map((s) => [s.child, s]));
  const children = [...new Set([...now.keys(), ...old.keys()])];
  return children.flatMap((child) => {
    const b = old.get(child) ?? null;
    const a = now.get(child) ?? null;
    return sameRelation(b, a) ? [] : [{ child, kind: changeKind(b, a), before: b, after: a }];
  });
}

export function diffScenes(before: Scene, after: Scene): SceneDiff {
  const ids = (scene: Scene) => new Set((scene.objects ?? []).map((o) => o.id));
  const was = ids(before);
  const is = ids(after);
  return {
    supports: diffSupports(before.supports ?? [], after.supports ?? []),
    objectsAdded: [...is].filter((id) => !was.has(id)),
    objectsRemoved: [...was].filter((id) => !is.has(id)),
    layoutChanged: JSON.stringify(before.layout) !== JSON.stringify(after.layout),
  };
}

function relationText(s: SupportRelation | null): string {
  if (!s) return "no supporter";
  const who =
    s.source === "manual"
      ? `by ${s.author ?? "someone"}`
      : `predicted${s.confidence === null || s.confidence === undefined ? "" : ` ${Math.round(s.confidence * 100)}%`}`;
  return `on ${s.parent} (${s.type}, ${who})`;
}

export function describeChange(change: SupportChange): string {
  const verb: Record<ChangeKind, string> = {
    added: "supporter set",
    removed: "supporter removed",
    moved: "new supporter",
    retyped: "type changed",
    confirmed: "prediction confirmed",
    provenance: "set again",
  };
  return `${change.child}: ${verb[change.kind]}: ${relationText(change.before)} → ${relationText(change.after)}`;
}
