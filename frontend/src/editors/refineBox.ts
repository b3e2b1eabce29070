// Where the Refine tool asks GrabCut to look: the object's box, grown to take in every
// foreground stroke whole (a person painting past the box means the object goes on there),
// inside the photo. Background strokes do not grow it: what is not the object can be anywhere.
import type { Stroke } from "@holiscene/schema";
import type { PixelRect } from "./maskPainting";

export type Box = [number, number, number, number];

export function refineBox(
  box: Readonly<Box>,
  foreground: readonly Stroke[],
  photo: PixelRect,
): Box {
  let [x1, y1, x2, y2] = box;
  for (const { points, radius } of foreground) {
    for (const [x, y] of points) {
      x1 = Math.min(x1, x - radius);
      y1 = Math.min(y1, y - radius);
      x2 = Math.max(x2, x + radius);
      y2 = Math.max(y2, y + radius);
    }
  }
  return [
    Math.max(photo.left, x1),
    Math.max(photo.top, y1),
    Math.min(photo.right, x2),
    Math.min(photo.bottom, y2),
  ];
}

/** The point moved into the photo (the server takes no stroke point outside it). */
export function intoPhoto([x, y]: readonly [number, number], photo: PixelRect): [number, number] {
  return [
    Math.min(photo.right, Math.max(photo.left, x)),
    Math.min(photo.bottom, Math.max(photo.top, y)),
  ];
}
