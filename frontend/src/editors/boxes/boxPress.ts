// What a press of the box tool starts: resizing the selected box by a handle, moving the selected
// box (pressed inside it), or drawing a new box (anywhere else, also over an object that is not
// selected: a pillow on a bed; with Shift, inside the selected box too). A press on an object
// that is not selected moves nothing: released without a drag, it selects that object. (Moving
// whatever object was under the pointer moved beds that fill half the photo, saved at once,
// when people meant to draw on them.)
import type { SceneObject } from "@holiscene/schema";
import { type Box, boxFromCorners, type Grip, gripAt } from "../boxGeometry";
import type { ImagePoint } from "../photoTools";
import { handleReach } from "./boxLayer";

export type Press =
  | {
      kind: "draw";
      start: ImagePoint;
      box: Box;
      /** What a release without a drag selects: the object pressed on, or none. */
      pick: string | null;
    }
  | {
      kind: "edit";
      id: string;
      grip: Grip;
      start: ImagePoint;
      from: Box;
      box: Box;
      moved: boolean;
    };

export interface PressContext {
  selected: SceneObject | null | undefined;
  /** The object under the pointer (ignored with Shift). */
  under: SceneObject | undefined;
  shift: boolean;
  /** Photo pixels per screen pixel. */
  pixelSize: number;
  width: number;
  height: number;
}

/** The press, and the object to select because of it (null: none; undefined: leave it). */
export function startPress(
  at: ImagePoint,
  context: PressContext,
): { press: Press; select?: string | null } {
  const { selected, shift } = context;
  const grip = selected
    ? gripAt(selected.bbox, at, handleReach(selected.bbox, context.pixelSize))
    : null;
  const object = shift ? undefined : context.under;
  const edit = (id: string, bbox: readonly number[], how: Grip): Press => {
    const from = [...bbox] as Box;
    return { kind: "edit", id, grip: how, start: at, from, box: from, moved: false };
  };
  // A handle of the selected box first; then its inside, unless another object is under the
  // pointer there (a pillow on the selected bed is selected by a click, drawn by a drag); else
  // a new box.
  if (selected && grip && !shift) {
    const onOther = object !== undefined && object.id !== selected.id;
    if (grip !== "move" || !onOther) return { press: edit(selected.id, selected.bbox, grip) };
  }
  const box = boxFromCorners(at, at, context.width, context.height);
  const pick = object?.id ?? null;
  // Pressed on nothing: the selection goes at once; on an object: chosen on release.
  return {
    press: { kind: "draw", start: at, box, pick },
    select: pick === null ? null : undefined,
  };
}
