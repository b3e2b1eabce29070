// What the geometry rules out before the Relation Network's scores are decoded, as the
// pipeline's support stages do (backend pipeline/stages/supports.py): the floor cannot hold
// up from below an object whose bottom edge is above the floor's horizon, unless a box just
// below it may hide a lower bottom; such an object is held by a wall, the ceiling or an
// object spanning part of its width. And no wall holds up from behind an object seen against
// the floor (the ray through its bottom edge meets the floor well before the wall). Without
// them the live suggestions would put back what the pipeline took away. (The pipeline's rule
// on an object too large for its class where it would stand is not here: it needs the
// classes' sizes and the masks.)
import type { Camera } from "@holiscene/schema";
import { invert, matMul, matVec, worldFromCv } from "../geometry/camera";
import { roomExits } from "../geometry/roomSurface";
import { STRUCTURAL_COLUMNS, SUPPORT_TYPE_ORDER } from "./supportModel";

type Box = readonly number[]; // x1, y1, x2, y2

// The same figures as the backend's (FLOOR_RAY_MIN_DROP, HIDING_*, SUPPORTER_OVERLAP,
// FLOOR_BEFORE_WALL).
const FLOOR_RAY_MIN_DROP = Math.sin((1.0 * Math.PI) / 180);
const HIDING_GAP = 0.03;
const HIDING_OVERLAP = 0.3;
const SUPPORTER_OVERLAP = 0.3;
const FLOOR_BEFORE_WALL = 1.6;

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

/** Per box: whether it is seen against the floor: the ray through the middle of its bottom
 * edge meets the room's floor FLOOR_BEFORE_WALL times nearer than the wall it leaves the room
 * through, so no wall holds it up from behind (false without a camera pose or a room). */
export function seenAgainstTheFloor(
  camera: Camera | null | undefined,
  roomCorners: readonly (readonly number[])[] | null | undefined,
  boxes: readonly Box[],
): boolean[] {
  return boxes.map((box) => {
    const exits = roomExits(
      [((box[0] ?? 0) + (box[2] ?? 0)) / 2, box[3] ?? 0],
      camera,
      roomCorners,
    );
    return (
      exits?.floor != null && exits.wall !== null && exits.wall > FLOOR_BEFORE_WALL * exits.floor
    );
  });
}

/** Zero, in place, the wall from behind in the rows of the objects seen against the floor,
 * unless nothing would be left; a changed row is scaled to sum to 1 again. */
export function ruleOutTheWall(
  probabilities: Float64Array,
  objects: number,
  againstFloor: readonly boolean[],
): void {
  const types = SUPPORT_TYPE_ORDER.length;
  const rowSize = (objects + STRUCTURAL_COLUMNS.length) * types;
  const wallBehind =
    (objects + STRUCTURAL_COLUMNS.indexOf("wall")) * types + SUPPORT_TYPE_ORDER.indexOf("behind");
  againstFloor.forEach((against, row) => {
    if (!against) return;
    const kept = probabilities.slice(row * rowSize, (row + 1) * rowSize);
    kept[wallBehind] = 0;
    const total = kept.reduce((sum, p) => sum + p, 0);
    if (total > 0)
      probabilities.set(
        kept.map((p) => p / total),
        row * rowSize,
      );
  });
}
