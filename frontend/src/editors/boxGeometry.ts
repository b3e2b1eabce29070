// Boxes on the photo as the box tool edits them: [x1, y1, x2, y2] in image pixels, always
// inside the photo and at least MIN_BOX_PX on a side. A press lands on one of 8 handles (the
// corners and the middles of the sides), inside the box (move), or outside it.

export type Box = [number, number, number, number];
export type Point = [number, number];
export type Handle = "nw" | "n" | "ne" | "e" | "se" | "s" | "sw" | "w";
export type Grip = Handle | "move";

export const HANDLES: readonly Handle[] = ["nw", "n", "ne", "e", "se", "s", "sw", "w"];
export const MIN_BOX_PX = 4;

/** Where a handle sits on `box`. */
export function handlePoint(box: readonly number[], handle: Handle): Point {
  const [x1 = 0, y1 = 0, x2 = 0, y2 = 0] = box;
  const x = handle.includes("w") ? x1 : handle.includes("e") ? x2 : (x1 + x2) / 2;
  const y = handle.includes("n") ? y1 : handle.includes("s") ? y2 : (y1 + y2) / 2;
  return [x, y];
}

/**
 * What a press at `at` grips: the nearest handle within `reach` pixels, else the inside of the
 * box (to move it), else nothing.
 */
export function gripAt(box: readonly number[], at: Point, reach: number): Grip | null {
  let best: Handle | null = null;
  let bestDistance = reach;
  for (const handle of HANDLES) {
    const [x, y] = handlePoint(box, handle);
    const distance = Math.max(Math.abs(x - at[0]), Math.abs(y - at[1]));
    if (distance <= bestDistance) {
      best = handle;
      bestDistance = distance;
    }
  }
  if (best) return best;
  const [x1 = 0, y1 = 0, x2 = 0, y2 = 0] = box;
  return at[0] >= x1 && at[0] <= x2 && at[1] >= y1 && at[1] <= y2 ? "move" : null;
}

const clamp = (value: number, low: number, high: number) => Math.min(high, Math.max(low, value));

/** The box spanned by two corners (any order), clamped to a photo of `width` x `height`. */
export function boxFromCorners(a: Point, b: Point, width: number, height: number): Box {
  const x1 = clamp(Math.min(a[0], b[0]), 0, width);
  const x2 = clamp(Math.max(a[0], b[0]), 0, width);
  const y1 = clamp(Math.min(a[1], b[1]), 0, height);
  const y2 = clamp(Math.max(a[1], b[1]), 0, height);
  return [x1, y1, x2, y2];
}

/** Whether a box is big enough to be an object (a smaller drag was a click). */
export const isBigEnough = (box: readonly number[]) =>
  (box[2] ?? 0) - (box[0] ?? 0) >= MIN_BOX_PX && (box[3] ?? 0) - (box[1] ?? 0) >= MIN_BOX_PX;

/**
 * `box` after dragging `grip` by (dx, dy): moved (kept whole inside the photo), or resized
 * (the dragged sides follow, clamped to the photo; past the opposite side the box flips; never
 * thinner than MIN_BOX_PX).
 */
export function dragBox(
  box: readonly number[],
  grip: Grip,
  dx: number,
  dy: number,
  width: number,
  height: number,
): Box {
  const [x1 = 0, y1 = 0, x2 = 0, y2 = 0] = box;
  if (grip === "move") {
    const mx = clamp(dx, -x1, width - x2);
    const my = clamp(dy, -y1, height - y2);
    return [x1 + mx, y1 + my, x2 + mx, y2 + my];
  }
  let [left, top, right, bottom] = [x1, y1, x2, y2];
  if (grip.includes("w")) left += dx;
  if (grip.includes("e")) right += dx;
  if (grip.includes("n")) top += dy;
  if (grip.includes("s")) bottom += dy;
  const [a, b] = [Math.min(left, right), Math.max(left, right)];
  const [c, d] = [Math.min(top, bottom), Math.max(top, bottom)];
  const out = boxFromCorners([a, c], [b, d], width, height);
  // Too thin: grow away from the side that did not move.
  if (out[2] - out[0] < MIN_BOX_PX) {
    if (grip.includes("w")) out[0] = Math.max(0, out[2] - MIN_BOX_PX);
    else out[2] = Math.min(width, out[0] + MIN_BOX_PX);
  }
  if (out[3] - out[1] < MIN_BOX_PX) {
    if (grip.includes("n")) out[1] = Math.max(0, out[3] - MIN_BOX_PX);
    else out[3] = Math.min(height, out[1] + MIN_BOX_PX);
  }
  return out;
}

/** A box to 0.01 px, as sent to the server. */
export const roundBox = (box: readonly number[]): Box =>
  box.map((v) => Math.round(v * 100) / 100) as Box;
