// What the geometry rules out before the Relation Network's scores are decoded, as the
// pipeline's support stages do (backend pipeline/stages/supports.py): the floor cannot hold
// up from below an object whose bottom edge is above the floor's horizon, unless a box just
// below it may hide a lower bottom; such an object is held by a wall, the ceiling or an
// object spanning part of its width. Without it the live suggestions would put back on the
// floor what the pipeline took off it.
import type { Camera } from "@holiscene/schema";
import { invert, matMul, matVec, worldFromCv } from "../geometry/camera";
import { STRUCTURAL_COLUMNS, SUPPORT_TYPE_ORDER } from "./supportModel";

type Box = readonly number[]; // x1, y1, x2, y2

// The same figures as the backend's (FLOOR_RAY_MIN_DROP, HIDING_*, SUPPORTER_OVERLAP).
const FLOOR_RAY_MIN_DROP = Math.sin((1.0 * Math.PI) / 180);
const HIDING_GAP = 0.03;
const HIDING_OVERLAP = 0.3;
const SUPPORTER_OVERLAP = 0.3;

const width = (b: Box) => Math.max(1, (b[2] ?? 0) - (b[0] ?? 0));
const overlapX = (a: Box, b: Box) =>
  Math.min(a[2] ?? 0, b[2] ?? 0) - Math.max(a[0] ?? 0, b[0] ?? 0);

/** Per box: whether the floor cannot hold it up from below (false without pitch and roll). */
export function offTheFloor(
  camera: Camera | null | undefined,
  boxes: readonly Box[],
  imageHeight: number,
): boolean[] {
  if (!camera || camera.pitch_deg === null || camera.roll_deg === null) {
    return boxes.map(() => false);
  }
  const worldFromPixel = matMul(worldFromCv(camera.pitch_deg, camera.roll_deg), invert(camera.K));
  return boxes.map((box, n) => {
    const ray = matVec(worldFromPixel, [((box[0] ?? 0) + (box[2] ?? 0)) / 2, box[3] ?? 0, 1]);
    const drop = -ray[1] / Math.hypot(...ray);
    const bottom = box[3] ?? 0;
    const hidden = boxes.some(
      (other, m) =>
        m !== n &&
        (other[1] ?? 0) <= bottom + HIDING_GAP * imageHeight &&
        (other[3] ?? 0) > bottom &&
        overlapX(box, other) >= HIDING_OVERLAP * width(box),
    );
    return drop < FLOOR_RAY_MIN_DROP && !hidden;
  });
}

/**
 * Zero, in place, the answers the geometry rules out in a probability table [N, N + 3, 2]
 * (flat) of the objects with `boxes`: for an object off the floor, the floor from below and
 * every object not spanning SUPPORTER_OVERLAP of its width, unless nothing would be left;
 * such a row is scaled to sum to 1 again (the decoding normalises rows anyway).
 */
export function ruleOutImpossible(
  probabilities: Float64Array,
  boxes: readonly Box[],
  offFloor: readonly boolean[],
): void {
  const n = boxes.length;
  const types = SUPPORT_TYPE_ORDER.length;
  const rowSize = (n + STRUCTURAL_COLUMNS.length) * types;
  const floorBelow = (n + STRUCTURAL_COLUMNS.indexOf("floor")) * types;
  offFloor.forEach((off, row) => {
    if (!off) return;
    const child = boxes[row] as Box;
    const kept = probabilities.slice(row * rowSize, (row + 1) * rowSize);
    kept[floorBelow + SUPPORT_TYPE_ORDER.indexOf("below")] = 0;
    boxes.forEach((other, column) => {
      if (column === row || overlapX(child, other) < SUPPORTER_OVERLAP * width(child)) {
        kept.fill(0, column * types, (column + 1) * types);
      }
    });
    const total = kept.reduce((sum, p) => sum + p, 0);
    if (total > 0)
      probabilities.set(
        kept.map((p) => p / total),
        row * rowSize,
      );
  });
}
