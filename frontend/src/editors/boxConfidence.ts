// How sure the box refiner is of an object's 3D box, for the object list: a reviewer looks
// first at the boxes it doubts. The chance is judged as on the synthetic rooms the refiner
// learned from; on real photos it ranks boxes, it is not a measured rate.
import type { SceneObject } from "@holiscene/schema";
import { percentText } from "../dom";

/** Below this chance of being right a box is marked as doubtful (the backend's stage note
 * counts with the same half: learning/box_refiner/confidence.py DOUBTFUL_CHANCE). */
export const DOUBTFUL_BOX = 0.5;

export interface BoxConfidenceText {
  /** Short, for the badge: "3D 62%". */
  text: string;
  /** Longer, for the tooltip. */
  title: string;
  doubtful: boolean;
}

type ConfidenceFields = Pick<SceneObject, "box_3d" | "box_3d_confidence">;

export function boxConfidence({
  box_3d,
  box_3d_confidence,
}: ConfidenceFields): BoxConfidenceText | null {
  if (!box_3d || typeof box_3d_confidence !== "number") return null;
  const percent = percentText(box_3d_confidence);
  const doubtful = box_3d_confidence < DOUBTFUL_BOX;
  return {
    text: `3D ${percent}`,
    title:
      `The box refiner gives this 3D box a ${percent} chance of overlapping the true box ` +
      "(3D IoU 0.15 or more), as judged on synthetic rooms" +
      (doubtful ? ": check it in the 3D view" : ""),
    doubtful,
  };
}
