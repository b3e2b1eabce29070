// What the geometry rules out before the Relation Network's scores are decoded, as the
// pipeline's support stages do (backend pipeline/stages/supports.py; the figures are the
// shared contract's, holiscene_schema/support_geometry.py): the floor cannot hold up from
// below an object whose bottom edge is above the floor's horizon (unless a box just below it
// may hide a lower bottom), nor one far too large for its class where that edge meets the
// floor (unless other objects' pixels just below it may hide a lower bottom); such an object
// is held by a wall, the ceiling or an object spanning part of its width. And no wall holds
// up from behind an object seen against the floor (the ray through its bottom edge meets the
// floor well before the wall). Without them the live suggestions would put back what the
// pipeline took away.
import type { Camera } from "@holiscene/schema";
import { SUPPORT_GEOMETRY } from "@holiscene/schema";
import {
  dot3,
  invert,
  type Matrix3Like,
  matMul,
  matVec,
  type Vec3,
  worldFromCv,
} from "../geometry/camera";
import { roomExits } from "../geometry/roomSurface";
import { maskSegments, type ObjectInput, roundHalfEven, type Segments } from "./preprocess";
import { STRUCTURAL_COLUMNS, SUPPORT_TYPE_ORDER } from "./supportModel";

type Box = readonly number[]; // x1, y1, x2, y2

// The contract's figures, as the backend's (holiscene_schema/support_geometry.py).
const {
  hiding_gap: HIDING_GAP,
  hiding_overlap: HIDING_OVERLAP,
  pixels_hiding_share: PIXELS_HIDING_SHARE,
  supporter_overlap: SUPPORTER_OVERLAP,
  floor_before_wall: FLOOR_BEFORE_WALL,
} = SUPPORT_GEOMETRY;
const FLOOR_RAY_MIN_DROP = Math.sin((SUPPORT_GEOMETRY.floor_ray_min_drop_deg * Math.PI) / 180);
const TOO_LARGE_LIMITS: Readonly<Record<string, readonly number[]>> =
  SUPPORT_GEOMETRY.too_large_limits;
const MAX_FLOOR_DISTANCE = 30; // camera heights, as the backend's ground.MAX_DISTANCE_M

const width = (b: Box) => Math.max(1, (b[2] ?? 0) - (b[0] ?? 0));
const overlapX = (a: Box, b: Box) =>
  Math.min(a[2] ?? 0, b[2] ?? 0) - Math.max(a[0] ?? 0, b[0] ?? 0);

/**
 * Per box: whether the floor cannot hold it up from below (false without pitch and roll):
 * its bottom edge is above the floor's horizon with no box just below that may hide a lower
 * bottom, or, given the `objects` (the boxes' own: classes and masks), it would be far too
 * large for its class standing where that edge meets the floor, with no other object's pixels
 * filling the strip just below it.
 */
export function offTheFloor(
  camera: Camera | null | undefined,
  boxes: readonly Box[],
  imageHeight: number,
  objects?: readonly ObjectInput[],
  imageWidth = 0,
): boolean[] {
  if (!camera || camera.pitch_deg === null || camera.roll_deg === null) {
    return boxes.map(() => false);
  }
  const worldFromPixel = matMul(worldFromCv(camera.pitch_deg, camera.roll_deg), invert(camera.K));
  // The masks are decoded only when an object is too large (rarely: most photos, never).
  let rows: Segments[] | null = null;
  const maskRows = (inputs: readonly ObjectInput[]) => {
    rows ??= inputs.map((o) => maskSegments(o, imageWidth, imageHeight));
    return rows;
  };
  return boxes.map((box, n) => {
    const ray = matVec(worldFromPixel, [((box[0] ?? 0) + (box[2] ?? 0)) / 2, box[3] ?? 0, 1]);
    const drop = -ray[1] / Math.hypot(...ray);
    if (drop < FLOOR_RAY_MIN_DROP) return !boxBelowMayHide(n, boxes, imageHeight);
    const cls = objects?.[n]?.cls;
    if (cls === undefined || !objects) return false;
    return (
      tooLargeToStandThere(worldFromPixel, cls, box) &&
      !pixelsBelowMayHide(n, boxes, maskRows(objects), imageHeight)
    );
  });
}

/** Whether another box starts just below box n's bottom edge (or above it) and reaches lower,
 * across enough of its width to hide where it really stands. */
function boxBelowMayHide(n: number, boxes: readonly Box[], imageHeight: number): boolean {
  const box = boxes[n] as Box;
  const bottom = box[3] ?? 0;
  return boxes.some(
    (other, m) =>
      m !== n &&
      (other[1] ?? 0) <= bottom + HIDING_GAP * imageHeight &&
      (other[3] ?? 0) > bottom &&
      overlapX(box, other) >= HIDING_OVERLAP * width(box),
  );
}

/** Whether other objects' pixels fill the strip just below box n's bottom edge across
 * PIXELS_HIDING_SHARE of its width (true when the photo's bottom edge cuts the strip). */
function pixelsBelowMayHide(
  n: number,
  boxes: readonly Box[],
  rows: readonly Segments[],
  imageHeight: number,
): boolean {
  const [x1, , x2, y2] = (boxes[n] as Box).map(roundHalfEven) as [number, number, number, number];
  const strip = Math.max(roundHalfEven(HIDING_GAP * imageHeight), 1);
  if (y2 + strip > imageHeight || x2 <= x1) return true;
  const below = new Uint8Array(x2 - x1);
  rows.forEach((segments, m) => {
    if (m === n) return;
    for (let y = y2; y < y2 + strip; y++) {
      const row = y - segments.top;
      if (row < 0 || row + 1 >= segments.offsets.length) continue;
      const end = segments.offsets[row + 1] as number;
      for (let k = segments.offsets[row] as number; k < end; k += 2) {
        const a = Math.max(segments.spans[k] as number, x1);
        const b = Math.min(segments.spans[k + 1] as number, x2);
        if (a < b) below.fill(1, a - x1, b - x1);
      }
    }
  });
  return below.reduce((sum, v) => sum + v, 0) / below.length >= PIXELS_HIDING_SHARE;
}

/**
 * Whether an object of class `cls` standing where its box's bottom edge meets the floor would
 * span more floor, or rise higher, than TOO_LARGE_LIMITS allows its class (camera heights;
 * false for a class without limits or a bottom edge that meets no floor in reach). The twin
 * of the backend's geometry/metric_scale.py too_large_to_stand_there.
 */
export function tooLargeToStandThere(worldFromPixel: Matrix3Like, cls: string, box: Box): boolean {
  const limits = TOO_LARGE_LIMITS[cls];
  if (!limits) return false;
  const [x1 = 0, y1 = 0, x2 = 0, y2 = 0] = box;
  const mid = (x1 + x2) / 2;
  const hits: Vec3[] = [];
  for (const pixel of [
    [x1, y2],
    [x2, y2],
    [mid, y2],
  ]) {
    const ray = matVec(worldFromPixel, [pixel[0] as number, pixel[1] as number, 1]);
    if (!(ray[1] < -1e-9)) return false; // the plane is not ahead of this ray
    const hit: Vec3 = [-ray[0] / ray[1], -1, -ray[2] / ray[1]];
    if (Math.hypot(...hit) > MAX_FLOOR_DISTANCE) return false;
    hits.push(hit);
  }
  const [left, right, base] = hits as [Vec3, Vec3, Vec3];
  const span = Math.hypot(left[0] - right[0], left[1] - right[1], left[2] - right[2]);
  return (
    span > (limits[0] as number) ||
    heightAbove(worldFromPixel, base, [mid, y1]) > (limits[1] as number)
  );
}

/** Height above `base` of the point on the vertical through it seen at `pixel` (the closest
 * points of the pixel's ray and that vertical), as the backend's ground.height_above. */
function heightAbove(worldFromPixel: Matrix3Like, base: Vec3, pixel: readonly number[]): number {
  const ray = matVec(worldFromPixel, [pixel[0] as number, pixel[1] as number, 1]);
  const rr = dot3(ray, ray);
  const rb = dot3(ray, base);
  const det = ray[1] * ray[1] - rr;
  return (rr * base[1] - rb * ray[1]) / det;
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
    keepUnlessEmpty(probabilities, kept, row * rowSize);
  });
}

/** Write row `kept` (a copy with answers zeroed), scaled to sum to 1, at `offset` of the
 * table, unless it zeroed every answer: then the geometry was wrong and the row stays. */
function keepUnlessEmpty(probabilities: Float64Array, kept: Float64Array, offset: number): void {
  const total = kept.reduce((sum, p) => sum + p, 0);
  if (total > 0)
    probabilities.set(
      kept.map((p) => p / total),
      offset,
    );
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
    keepUnlessEmpty(probabilities, kept, row * rowSize);
  });
}
