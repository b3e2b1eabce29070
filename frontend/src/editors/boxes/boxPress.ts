// What a press of the box tool starts: resizing the selected box by a handle, moving an object's
// box (the one under the pointer, or the selected one when pressed inside it), or drawing a new
// box (always with Shift: one inside another object's, a pillow on a bed).
import type { SceneObject } from "@holiscene/schema";
import { type Box, boxFromCorners, type Grip, gripAt } from "../boxGeometry";
import type { ImagePoint } from "../photoTools";
import { HANDLE_PX } from "./boxLayer";

export type Press =
  | { kind: "draw"; start: ImagePoint; box: Box }
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
  const grip = selected ? gripAt(selected.bbox, at, HANDLE_PX * context.pixelSize) : null;
  const object = shift ? undefined : context.under;
  const edit = (id: string, bbox: readonly number[], how: Grip): Press => {
    const from = [...bbox] as Box;
    return { kind: "edit", id, grip: how, start: at, from, box: from, moved: false };
  };
  // A handle of the selected box first; then the object under the pointer (a smaller one
  // inside the selected box too); then the selected box's inside; else a new box.
  if (selected && grip && grip !== "move" && !shift)
    return { press: edit(selected.id, selected.bbox, grip) };
  if (object) return { press: edit(object.id, object.bbox, "move"), select: object.id };
  if (selected && grip === "move" && !shift)
    return { press: edit(selected.id, selected.bbox, "move") };
  const box = boxFromCorners(at, at, context.width, context.height);
  return { press: { kind: "draw", start: at, box }, select: null };
}
