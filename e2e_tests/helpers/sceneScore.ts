// Scoring an annotated scene against a synthetic room's truth (gt.json): each true object is
// matched to at most one saved object by box overlap (IoU >= 0.5, best pairs first), then the
// matched pairs are checked for class, mask overlap and supporter. Ids differ between the two
// (the annotator's objects get the app's ids), so supporters are compared through the match.
import type { Mask, Scene, SceneObject, SupportRelation } from "@holiscene/schema";

export const MATCH_IOU = 0.5;
const STRUCTURAL = new Set(["floor", "wall", "ceiling"]);

export function boxIou(a: readonly number[], b: readonly number[]): number {
  const [ax1 = 0, ay1 = 0, ax2 = 0, ay2 = 0] = a;
  const [bx1 = 0, by1 = 0, bx2 = 0, by2 = 0] = b;
  const w = Math.min(ax2, bx2) - Math.max(ax1, bx1);
  const h = Math.min(ay2, by2) - Math.max(ay1, by1);
  if (w <= 0 || h <= 0) return 0;
  const inter = w * h;
  return inter / ((ax2 - ax1) * (ay2 - ay1) + (bx2 - bx1) * (by2 - by1) - inter);
}

/** The pixels a mask covers, as indices into a `width`-wide image (runs: 0s first, then 1s). */
export function maskPixels(mask: Mask, width: number): Set<number> {
  const [w] = mask.size;
  const [ox, oy] = mask.origin;
  const pixels = new Set<number>();
  let at = 0;
  mask.rle.forEach((run, i) => {
    if (i % 2 === 1) {
      for (let p = at; p < at + run; p++) {
        pixels.add((oy + Math.floor(p / w)) * width + ox + (p % w));
      }
    }
    at += run;
  });
  return pixels;
}

/** IoU of two masks on a `width`-wide photo; 0 when either is missing or both are empty. */
export function maskIou(a: Mask | null | undefined, b: Mask | null | undefined, width: number) {
  if (!a || !b) return 0;
  const pa = maskPixels(a, width);
  const pb = maskPixels(b, width);
  let inter = 0;
  for (const p of pa) if (pb.has(p)) inter += 1;
  const union = pa.size + pb.size - inter;
  return union === 0 ? 0 : inter / union;
}

/** True id -> saved id, each side used once, the best-overlapping pairs first. */
export function matchObjects(
  truth: readonly SceneObject[],
  saved: readonly SceneObject[],
  minIou = MATCH_IOU,
): Map<string, string> {
  const pairs = truth.flatMap((t) =>
    saved.map((s) => ({ t: t.id, s: s.id, iou: boxIou(t.bbox, s.bbox) })),
  );
  pairs.sort((a, b) => b.iou - a.iou);
  const match = new Map<string, string>();
  const used = new Set<string>();
  for (const { t, s, iou } of pairs) {
    if (iou < minIou) break;
    if (match.has(t) || used.has(s)) continue;
    match.set(t, s);
    used.add(s);
  }
  return match;
}

export interface ObjectScore {
  truthId: string;
  truthClass: string;
  savedId: string | null;
  savedClass: string | null;
  boxIou: number;
  maskIou: number;
  truthParent: string | null;
  /** The saved supporter, as the true object it was matched to (or floor/wall/ceiling). */
  savedParent: string | null;
}

export interface SceneScore {
  objects: number;
  saved: number;
  matched: number;
  /** Saved objects matched to no true one. */
  extra: number;
  classesRight: number;
  meanMaskIou: number;
  /** Matched objects whose mask overlaps the truth's by at least 0.5. */
  masksGood: number;
  supportersRight: number;
  typesRight: number;
  rows: ObjectScore[];
}

/** How far `saved` is from `truth` (both full scenes of the same photo). */
export function scoreScene(truth: Scene, saved: Scene): SceneScore {
  const trueObjects = truth.objects ?? [];
  const savedObjects = saved.objects ?? [];
  const width = truth.image.width;
  const match = matchObjects(trueObjects, savedObjects);
  const back = new Map([...match].map(([t, s]) => [s, t]));
  const byId = new Map(savedObjects.map((o) => [o.id, o]));
  const support = (scene: Scene) =>
    new Map((scene.supports ?? []).map((s): [string, SupportRelation] => [s.child, s]));
  const trueSupport = support(truth);
  const savedSupport = support(saved);
  const asTruth = (parent: string | undefined) =>
    parent === undefined ? null : STRUCTURAL.has(parent) ? parent : (back.get(parent) ?? parent);

  const rows = trueObjects.map((t): ObjectScore => {
    const savedId = match.get(t.id) ?? null;
    const s = savedId ? byId.get(savedId) : undefined;
    return {
      truthId: t.id,
      truthClass: t.class,
      savedId,
      savedClass: s?.class ?? null,
      boxIou: s ? boxIou(t.bbox, s.bbox) : 0,
      maskIou: s ? maskIou(t.mask, s.mask, width) : 0,
      truthParent: trueSupport.get(t.id)?.parent ?? null,
      savedParent: savedId ? asTruth(savedSupport.get(savedId)?.parent) : null,
    };
  });
  const matched = rows.filter((r) => r.savedId !== null);
  const typeOf = (r: ObjectScore) => ({
    truth: trueSupport.get(r.truthId)?.type,
    saved: r.savedId ? savedSupport.get(r.savedId)?.type : undefined,
  });
  return {
    objects: trueObjects.length,
    saved: savedObjects.length,
    matched: matched.length,
    extra: savedObjects.length - matched.length,
    classesRight: matched.filter((r) => r.savedClass === r.truthClass).length,
    meanMaskIou: matched.length
      ? matched.reduce((sum, r) => sum + r.maskIou, 0) / matched.length
      : 0,
    masksGood: matched.filter((r) => r.maskIou >= MATCH_IOU).length,
    supportersRight: matched.filter(
      (r) => r.truthParent !== null && r.savedParent === r.truthParent,
    ).length,
    typesRight: matched.filter((r) => {
      const { truth, saved } = typeOf(r);
      return truth !== undefined && truth === saved;
    }).length,
    rows,
  };
}
