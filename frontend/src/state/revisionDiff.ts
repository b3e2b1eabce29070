// What changed between two revisions of a scene (the history's diff).
import type { Scene, SceneObject, SupportRelation } from "@holiscene/schema";
import { percentText } from "../dom";
import { objectClassText } from "./classNames";
import { sameRelation } from "./supportGraph";

export type ChangeKind = "added" | "removed" | "moved" | "retyped" | "confirmed" | "provenance";

export interface SupportChange {
  child: string;
  kind: ChangeKind;
  before: SupportRelation | null;
  after: SupportRelation | null;
}

/** An object of both revisions, and what of it changed: what a person sees on the photo
 * (class, box, mask) and what the placement made of it (3D box, shape). */
export interface ObjectChange {
  id: string;
  /** "class otherprop → chair", "box 10,20–110,220 → 12,20–110,220", "mask redrawn" */
  drawn: string[];
  /** "3D box", "shape" */
  placed: string[];
}

export interface SceneDiff {
  supports: SupportChange[];
  objectsAdded: string[];
  objectsRemoved: string[];
  objectsChanged: ObjectChange[];
  layoutChanged: boolean;
}

const same = (a: unknown, b: unknown) => JSON.stringify(a ?? null) === JSON.stringify(b ?? null);

/** A box as whole pixels, left,top–right,bottom: a reviewer checks the edge they asked for. */
const boxText = (bbox: readonly number[]) => {
  const [x1, y1, x2, y2] = bbox.map((v) => Math.round(v));
  return `${x1},${y1}–${x2},${y2}`;
};

function objectChange(before: SceneObject, after: SceneObject): ObjectChange | null {
  const drawn = [
    objectClassText(before) !== objectClassText(after) &&
      `class ${objectClassText(before)} → ${objectClassText(after)}`,
    !same(before.bbox, after.bbox) && `box ${boxText(before.bbox)} → ${boxText(after.bbox)}`,
    !same(before.mask, after.mask) && "mask redrawn",
  ].filter((part): part is string => typeof part === "string");
  const placed = [
    !same(before.box_3d, after.box_3d) && "3D box",
    !same(before.mesh, after.mesh) && "shape",
  ].filter((part): part is string => typeof part === "string");
  return drawn.length + placed.length > 0 ? { id: after.id, drawn, placed } : null;
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
  const old = new Map((before.objects ?? []).map((o) => [o.id, o]));
  const is = new Set((after.objects ?? []).map((o) => o.id));
  const kept = (after.objects ?? []).flatMap((o) => {
    const was = old.get(o.id);
    return was ? [[was, o] as const] : [];
  });
  return {
    supports: diffSupports(before.supports ?? [], after.supports ?? []),
    objectsAdded: [...is].filter((id) => !old.has(id)),
    objectsRemoved: [...old.keys()].filter((id) => !is.has(id)),
    objectsChanged: kept.flatMap(([was, now]) => objectChange(was, now) ?? []),
    layoutChanged: !same(before.layout, after.layout) || !same(before.camera, after.camera),
  };
}

function relationText(s: SupportRelation | null): string {
  if (!s) return "no supporter";
  const who =
    s.source === "manual"
      ? `by ${s.author ?? "someone"}`
      : `predicted${s.confidence === null || s.confidence === undefined ? "" : ` ${percentText(s.confidence)}`}`;
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
