// What the object detector saw on the photo, kept for the class picker: for a box (one drawn,
// or an object's), the classes of the detector's boxes at the same place down to HINT_SCORE
// (below the score that makes an offer too), the three most likely. The picker lists them
// first, so a box the detector found with the wrong class, or saw too faintly to offer, mostly
// gets its class with one key (the suggester's boxes join them: objectSuggestions.ts); fainter
// or more guesses would push the classes the scene uses out of the nine lines a digit picks.
import { type Box, boxIou, type DetectedBox } from "../../inference/detectorTensor";

/** The detector's boxes down to this score are kept as hints (offers need DETECTOR_MODEL's). */
export const HINT_SCORE = 0.1;

/** At most this many classes are hinted for a box. */
export const MAX_HINTS = 3;

/** A detector box tells the class of a box it overlaps at least this much. */
export const HINT_IOU = 0.5;

/** A class the detector saw at a box, with its best score there. */
export interface LikelyClass {
  cls: string;
  score: number;
}

/** The classes of `seen` boxes at `bbox` (IoU >= HINT_IOU), best score first, each once, at
 * most MAX_HINTS. */
export function likelyClasses(
  bbox: readonly number[],
  seen: readonly Pick<DetectedBox, "bbox" | "score" | "cls">[],
): LikelyClass[] {
  const best = new Map<string, number>();
  for (const box of seen) {
    if (box.score < HINT_SCORE || boxIou(bbox, box.bbox) < HINT_IOU) continue;
    best.set(box.cls, Math.max(best.get(box.cls) ?? 0, box.score));
  }
  return [...best]
    .map(([cls, score]) => ({ cls, score }))
    .sort((a, b) => b.score - a.score || a.cls.localeCompare(b.cls))
    .slice(0, MAX_HINTS);
}

/** The last detector run's boxes of each scene (this page's visit; none before a run). */
class ClassHints {
  private readonly seen = new Map<string, DetectedBox[]>();

  set(sceneId: string, boxes: readonly DetectedBox[]): void {
    this.seen.set(
      sceneId,
      boxes.filter((b) => b.score >= HINT_SCORE),
    );
  }

  /** Another detector's boxes on the same run's photo, hints beside the first's: the
   * suggester's, which name the classes COCO lacks (on the real photos' given boxes the right
   * class comes among the hints for 49% of them instead of 37%: docs/detector.md). */
  add(sceneId: string, boxes: readonly DetectedBox[]): void {
    const kept = boxes.filter((b) => b.score >= HINT_SCORE);
    this.seen.set(sceneId, [...(this.seen.get(sceneId) ?? []), ...kept]);
  }

  /** The likely classes of `bbox` in the scene's photo (none before the detector ran). */
  at(sceneId: string, bbox: readonly number[] | Box): LikelyClass[] {
    return likelyClasses(bbox, this.seen.get(sceneId) ?? []);
  }
}

export const classHints = new ClassHints();
