// Pinhole camera with pitch and roll in the contract's world frame: the TypeScript twin of
// backend/src/holiscene/geometry/camera.py (same names, same formulas).
// Frames: OpenCV camera (x right, y down, z forward; what K maps to pixels) and world (origin
// at the camera centre, x horizontal forward, y up, z right). worldFromCv = Rz(-pitch) Rx(roll)
// CV_TO_FUR: roll about the optical axis first, then pitch down about the right axis.

export type Vec3 = [number, number, number];
export type Mat3 = [Vec3, Vec3, Vec3];
export type Point2 = [number, number];
/** A 3x3 matrix as the contract sends it (rows), or any array of rows. */
export type Matrix3Like = readonly (readonly number[])[];

// OpenCV (right, down, forward) -> (forward, up, right); it is its own inverse.
const CV_TO_FUR: Mat3 = [
  [0, 0, 1],
  [0, -1, 0],
  [1, 0, 0],
];

export const degrees = (radians: number): number => (radians * 180) / Math.PI;
export const radians = (deg: number): number => (deg * Math.PI) / 180;

export function rotX(angle: number): Mat3 {
  const c = Math.cos(angle);
  const s = Math.sin(angle);
  return [
    [1, 0, 0],
    [0, c, -s],
    [0, s, c],
  ];
}

export function rotY(angle: number): Mat3 {
  const c = Math.cos(angle);
  const s = Math.sin(angle);
  return [
    [c, 0, s],
    [0, 1, 0],
    [-s, 0, c],
  ];
}

export function rotZ(angle: number): Mat3 {
  const c = Math.cos(angle);
  const s = Math.sin(angle);
  return [
    [c, -s, 0],
    [s, c, 0],
    [0, 0, 1],
  ];
}

export function matMul(a: Matrix3Like, b: Matrix3Like): Mat3 {
  const row = (i: number): Vec3 => [0, 1, 2].map((j) => dot3(a[i] ?? [], column(b, j))) as Vec3;
  return [row(0), row(1), row(2)];
}

export function transpose(m: Matrix3Like): Mat3 {
  return [column(m, 0), column(m, 1), column(m, 2)];
}

export function column(m: Matrix3Like, j: number): Vec3 {
  return [m[0]?.[j] ?? 0, m[1]?.[j] ?? 0, m[2]?.[j] ?? 0];
}

export function matVec(m: Matrix3Like, v: readonly number[]): Vec3 {
  return [dot3(m[0] ?? [], v), dot3(m[1] ?? [], v), dot3(m[2] ?? [], v)];
}

/** a - b, for 3-vectors (a room's corners come as plain arrays). */
export const sub3 = (a: readonly number[], b: readonly number[]): Vec3 => [
  (a[0] ?? 0) - (b[0] ?? 0),
  (a[1] ?? 0) - (b[1] ?? 0),
  (a[2] ?? 0) - (b[2] ?? 0),
];

export function dot3(a: readonly number[], b: readonly number[]): number {
  return (a[0] ?? 0) * (b[0] ?? 0) + (a[1] ?? 0) * (b[1] ?? 0) + (a[2] ?? 0) * (b[2] ?? 0);
}

export function cross(a: Vec3, b: Vec3): Vec3 {
  return [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]];
}

export function rowOf(m: Matrix3Like, i: number): Vec3 {
  const r = m[i];
  return [r?.[0] ?? 0, r?.[1] ?? 0, r?.[2] ?? 0];
}

export function determinant(m: Matrix3Like): number {
  return dot3(rowOf(m, 0), cross(rowOf(m, 1), rowOf(m, 2)));
}

/** The inverse of an invertible 3x3 matrix. */
export function invert(m: Matrix3Like): Mat3 {
  const [r0, r1, r2] = [rowOf(m, 0), rowOf(m, 1), rowOf(m, 2)];
  const det = dot3(r0, cross(r1, r2));
  // The inverse's columns are the cross products of the rows, over the determinant.
  const columns = [cross(r1, r2), cross(r2, r0), cross(r0, r1)];
  return transpose(columns.map((c) => c.map((x) => x / det)));
}

/** Rotation taking OpenCV camera coordinates to world coordinates. */
export function worldFromCv(pitchDeg: number, rollDeg: number): Mat3 {
  return matMul(matMul(rotZ(-radians(pitchDeg)), rotX(radians(rollDeg))), CV_TO_FUR);
}

/** Pixels of world points; null for a point behind the camera (as the layout's corners_2d). */
export function projectPoints(
  K: Matrix3Like,
  pitchDeg: number,
  rollDeg: number,
  points: readonly Vec3[],
): (Point2 | null)[] {
  const camFromWorld = transpose(worldFromCv(pitchDeg, rollDeg));
  return points.map((point) => {
    const cam = matVec(camFromWorld, point);
    if (cam[2] <= 1e-9) return null;
    const [x, y, w] = matVec(K, cam);
    return [x / w, y / w];
  });
}

/**
 * Pitch and roll (degrees) from the world's up direction in OpenCV camera coordinates.
 * World up in (forward, up, right) camera coordinates is (-sin p, cos p cos r, -cos p sin r).
 */
export function pitchRollFromUpDirection(upCv: Vec3): [number, number] {
  const norm = Math.hypot(...upCv);
  // The direction must point up in the image (negative OpenCV y).
  const sign = upCv[1] > 0 ? -1 : 1;
  const [right, down, forward] = upCv.map((x) => (sign * x) / norm) as Vec3;
  const pitch = degrees(Math.asin(Math.max(-1, Math.min(1, -forward))));
  const roll = degrees(Math.atan2(-right, -down));
  return [pitch, roll];
}
