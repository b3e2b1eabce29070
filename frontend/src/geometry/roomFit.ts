// Room cuboid and camera pitch/roll from the room's layout corners in the image: the
// TypeScript twin of backend/src/holiscene/geometry/room_fit.py, whose docstring describes the
// algorithm. Both follow it step for step (same start, same damping, same stopping rule, same
// error messages) and are checked against shared_schema/vectors/room_fit.json: change them
// together and regenerate the vectors (`python -m holiscene.twin_vectors.room_fit`).
import { BOX_CORNER_SIGNS, boxCorners } from "./boxes";
import {
  cross,
  degrees,
  determinant,
  dot3,
  invert,
  type Mat3,
  type Matrix3Like,
  matVec,
  type Point2,
  pitchRollFromUpDirection,
  projectPoints,
  radians,
  rotY,
  rowOf,
  transpose,
  type Vec3,
  worldFromCv,
} from "./camera";

export const MIN_CORNERS = 4;
export const MAX_TRIALS = 200;
export const LAMBDA_INIT = 1e-3;
export const LAMBDA_MAX = 1e10;
export const STEP_TOLERANCE = 1e-10;
/** A known corner must stay this far in front of the camera (metres along the optical axis). */
export const MIN_DEPTH = 1e-6;
/** Below this a cross product or a ray's vertical component counts as zero (unit vectors). */
export const PARALLEL_TOLERANCE = 1e-9;

/** Floor-plan edges between vertical edges (a, b): a -> b is the room's local +x (0) or +z (2). */
const PLAN_EDGES: readonly (readonly [number, number, 0 | 2])[] = [
  [0, 1, 0],
  [3, 2, 0],
  [0, 3, 2],
  [1, 2, 2],
];
/** A wall: its axis in the plan (0 = local x, 1 = local z) and side, and its vertical edges. */
interface Wall {
  axis: 0 | 1;
  side: -1 | 1;
  edges: readonly [number, number];
}
const WALLS: readonly Wall[] = [
  { axis: 0, side: -1, edges: [0, 3] },
  { axis: 0, side: 1, edges: [1, 2] },
  { axis: 1, side: -1, edges: [0, 1] },
  { axis: 1, side: 1, edges: [2, 3] },
];
/** Parameters: pitch, roll, yaw (radians), centre x, centre z, depth, height, width. */
const N_PARAMS = 8;
type Params = [number, number, number, number, number, number, number, number];

/** Corners as the layout sends them: 8 pixel points, null for a corner behind the camera. */
export type Corners2d = readonly (readonly number[] | null)[];

export interface RoomBox {
  center: Vec3; // world, metres
  size: Vec3; // depth (own x), height, width (own z)
  yawDeg: number; // about world +y, in (-180, 180]
}

export interface RoomFit {
  pitchDeg: number;
  rollDeg: number;
  room: RoomBox;
  /** World corners (8), in the order of the corners given. */
  corners3d: Vec3[];
  /** Root mean square distance between known and fitted corners, pixels. */
  rmsPx: number;
  /** Levenberg-Marquardt steps proposed. */
  trials: number;
  converged: boolean;
}

/** A room to start from when the corners give no usable start (room_fit.py's step 3). */
export interface RoomStart {
  pitchDeg: number;
  rollDeg: number;
  room: RoomBox;
}

export interface FitRoomOptions {
  /** Distance from the camera to a wall without known corners (ignored when every wall has one). */
  unseenWallDistance?: number | null;
  /** The room shown before the last corner moved: the start when the corners' own fails. */
  start?: RoomStart | null;
}

/** The corners do not determine a room (the message says why). */
export class RoomFitError extends Error {
  override name = "RoomFitError";
}

/** Why the known corners cannot determine the room, or null when they can. */
export function cornerCoverageProblem(
  corners2d: Corners2d,
  unseenWallDistance: number | null = null,
): string | null {
  if (corners2d.length !== 8) {
    const count = corners2d.length;
    return `expected 8 layout corners (null for a corner behind the camera), got ${count}`;
  }
  const known = corners2d.map((corner) => corner !== null);
  const count = (flags: boolean[]) => flags.filter(Boolean).length;
  if (count(known) < MIN_CORNERS) {
    return `fewer than ${MIN_CORNERS} known corners (${count(known)}): the room is not determined`;
  }
  const edgeIndices = [0, 1, 2, 3];
  if (count(edgeIndices.map((i) => known[i] === true && known[i + 4] === true)) < 2) {
    return (
      "fewer than two vertical room edges with both corners known (corners i and i + 4): " +
      "the vertical direction, hence pitch and roll, is not determined"
    );
  }
  const located = edgeIndices.map((i) => known[i] === true || known[i + 4] === true);
  if (count(located) >= 3) return null;
  if (located[0] === located[2]) {
    return "only two opposite vertical room edges have known corners: the yaw is not determined";
  }
  if (unseenWallDistance === null) {
    return (
      "a wall has no known corner: its position is not determined " +
      "(give unseen_wall_distance, its distance from the camera)"
    );
  }
  return null;
}

/** Camera pitch/roll and room box from the layout corners; throws RoomFitError if undetermined. */
export function fitRoom(
  K: Matrix3Like,
  corners2d: Corners2d,
  cameraHeight: number,
  options: FitRoomOptions = {},
): RoomFit {
  const observations = checkedObservations(K, corners2d, cameraHeight, options.unseenWallDistance);
  const fallback = options.start ? paramsOf(options.start) : null;
  let guess: Float64Array;
  try {
    guess = initialGuess(observations);
  } catch (error) {
    if (fallback === null || !(error instanceof RoomFitError)) throw error;
    guess = fallback;
  }
  const result = levenbergMarquardt(observations, guess, fallback);
  const { params, residuals } = result;
  if (Math.min(at(params, 5), at(params, 6), at(params, 7)) <= 0) {
    throw new RoomFitError("the fit turned the room inside out: the corners are inconsistent");
  }
  const room = roomBox(params, observations.cameraHeight);
  const n = observations.pixels.length;
  let squares = 0;
  for (let r = 0; r < 2 * n; r++) squares += at(residuals, r) ** 2;
  return {
    pitchDeg: degrees(at(params, 0)),
    rollDeg: degrees(at(params, 1)),
    room,
    corners3d: boxCorners(room.center, room.size, room.yawDeg),
    rmsPx: Math.sqrt(squares / n),
    trials: result.trials,
    converged: result.converged,
  };
}

/** The layout's corners_2d for world corners: pixels, null for a corner behind the camera. */
export const projectRoomCorners = projectPoints;

interface Observations {
  K: Mat3;
  indices: number[]; // which of the 8 corners are known
  pixels: Point2[]; // their image points
  cameraHeight: number;
  unseenWall: Wall | null; // the wall without known corners, if any
  unseenWallDistance: number;
}

/** Element i of an array that has it (the indices here are fixed by construction). */
function at(values: ArrayLike<number>, i: number): number {
  return values[i] as number;
}

function checkedObservations(
  K: Matrix3Like,
  corners2d: Corners2d,
  cameraHeight: number,
  unseenWallDistance: number | null | undefined,
): Observations {
  const isMatrix3 = K.length === 3 && K.every((row) => row.length === 3);
  if (!isMatrix3 || !K.every((row) => row.every(Number.isFinite))) {
    throw new RoomFitError("K must be a 3x3 matrix of finite numbers");
  }
  if (Math.abs(determinant(K)) < 1e-12) throw new RoomFitError("K must be invertible");
  if (!(Number.isFinite(cameraHeight) && cameraHeight > 0)) {
    throw new RoomFitError("camera_height must be a positive number of metres");
  }
  const prior = unseenWallDistance ?? null;
  if (prior !== null && !(Number.isFinite(prior) && prior > 0)) {
    throw new RoomFitError("unseen_wall_distance must be a positive number of metres");
  }
  const problem = cornerCoverageProblem(corners2d, prior);
  if (problem !== null) throw new RoomFitError(problem);
  const indices: number[] = [];
  const pixels: Point2[] = [];
  corners2d.forEach((corner, i) => {
    if (corner === null) return;
    if (corner.length !== 2 || !corner.every(Number.isFinite)) {
      throw new RoomFitError("each known corner must be two finite pixel coordinates");
    }
    indices.push(i);
    pixels.push([at(corner, 0), at(corner, 1)]);
  });
  const unseen = WALLS.filter(
    (wall) => !wall.edges.some((i) => indices.includes(i) || indices.includes(i + 4)),
  );
  return {
    K: [rowOf(K, 0), rowOf(K, 1), rowOf(K, 2)],
    indices,
    pixels,
    cameraHeight,
    unseenWall: unseen[0] ?? null,
    unseenWallDistance: prior ?? 0,
  };
}

function unit<T extends number[]>(vector: T, what: string): T {
  const norm = Math.hypot(...vector);
  if (norm < PARALLEL_TOLERANCE) throw new RoomFitError(`degenerate layout: ${what}`);
  return vector.map((x) => x / norm) as T;
}

const mean = (values: readonly number[]): number =>
  values.reduce((sum, x) => sum + x, 0) / values.length;

/** Closed-form start for the optimiser (steps 1-3 of room_fit.py's docstring). */
function initialGuess(observations: Observations): Float64Array {
  const h = observations.cameraHeight;
  const kInverse = invert(observations.K);
  const rayCv = new Map<number, Vec3>();
  observations.indices.forEach((corner, k) => {
    const [u, v] = observations.pixels[k] as Point2;
    rayCv.set(corner, matVec(kInverse, [u, v, 1]));
  });
  const cvRay = (i: number): Vec3 => rayCv.get(i) as Vec3;
  const edges = [0, 1, 2, 3].filter((i) => rayCv.has(i) && rayCv.has(i + 4));

  // 1. Vertical direction (in OpenCV camera coordinates) -> pitch, roll.
  const normals = edges.map((i) =>
    unit(cross(cvRay(i), cvRay(i + 4)), `corners ${i} and ${i + 4} coincide`),
  );
  let vertical: Vec3 = [0, 0, 0];
  for (let a = 0; a < normals.length; a++) {
    for (let b = a + 1; b < normals.length; b++) {
      const meet = cross(normals[a] as Vec3, normals[b] as Vec3);
      const sign = meet[1] > 0 ? -1 : 1; // up in the image: negative OpenCV y
      vertical = [
        vertical[0] + sign * meet[0],
        vertical[1] + sign * meet[1],
        vertical[2] + sign * meet[2],
      ];
    }
  }
  vertical = unit(vertical, "the vertical room edges lie on one line in the image");
  const [pitchDeg, rollDeg] = pitchRollFromUpDirection(vertical);
  const toWorld = worldFromCv(pitchDeg, rollDeg);
  const rays = new Map<number, Vec3>();
  for (const [i, r] of rayCv) rays.set(i, matVec(toWorld, r));
  const ray = (i: number): Vec3 => rays.get(i) as Vec3;

  /** Where corner i's ray meets the horizontal plane at height y. */
  const onPlane = (i: number, y: number): Vec3 => {
    const r = ray(i);
    if (r[1] * y <= PARALLEL_TOLERANCE * Math.abs(y)) {
      const side = y < 0 ? "below" : "above";
      throw new RoomFitError(`corner ${i} is not ${side} the horizon: check the corner order`);
    }
    const t = y / r[1];
    return [r[0] * t, r[1] * t, r[2] * t];
  };

  // 2. Ceiling height: the point of each ceiling ray above its floor corner.
  const ceilingHeights = edges.map((i) => {
    const floorPoint = onPlane(i, -h);
    const upRay = ray(i + 4);
    const t =
      (upRay[0] * floorPoint[0] + upRay[2] * floorPoint[2]) / (upRay[0] ** 2 + upRay[2] ** 2);
    return t * upRay[1];
  });
  const ceiling = mean(ceilingHeights);
  if (ceiling + h <= 0) {
    throw new RoomFitError("the ceiling corners lie below the floor: check the corner order");
  }

  // 3. Floor plan: (x, z) of each vertical edge from its floor corner, else its ceiling corner.
  const plan = new Map<number, [number, number]>();
  for (let i = 0; i < 4; i++) {
    const point = rays.has(i) ? onPlane(i, -h) : rays.has(i + 4) ? onPlane(i + 4, ceiling) : null;
    if (point !== null) plan.set(i, [point[0], point[2]]);
  }
  // Each plan edge, turned to local +x, votes (cos yaw, sin yaw) weighted by its length:
  // local +x is world (cos yaw, -sin yaw) and local +z is (sin yaw, cos yaw) in (x, z).
  let heading: [number, number] = [0, 0];
  for (const [a, b, axis] of PLAN_EDGES) {
    const from = plan.get(a);
    const to = plan.get(b);
    if (from === undefined || to === undefined) continue;
    const dx = to[0] - from[0];
    const dz = to[1] - from[1];
    heading = axis === 0 ? [heading[0] + dx, heading[1] - dz] : [heading[0] + dz, heading[1] + dx];
  }
  heading = unit(heading, "the room's corners coincide on the floor plan");
  const yaw = Math.atan2(heading[1], heading[0]);
  const cosYaw = Math.cos(yaw);
  const sinYaw = Math.sin(yaw);
  const local = new Map<number, [number, number]>();
  for (const [i, [x, z]] of plan) local.set(i, [x * cosYaw - z * sinYaw, x * sinYaw + z * cosYaw]);

  /** The wall's local coordinate: mean of its known plan corners, or the prior. */
  const wall = (axis: 0 | 1, side: -1 | 1): number => {
    const edgesOnWall = WALLS.find((w) => w.axis === axis && w.side === side)?.edges ?? [];
    const onWall = edgesOnWall.flatMap((i) => {
      const point = local.get(i);
      return point === undefined ? [] : [point[axis]];
    });
    return onWall.length === 0 ? side * observations.unseenWallDistance : mean(onWall);
  };

  const [xLo, xHi, zLo, zHi] = [wall(0, -1), wall(0, 1), wall(1, -1), wall(1, 1)];
  const depth = xHi - xLo;
  const width = zHi - zLo;
  const height = ceiling + h;
  if (depth <= 0 || width <= 0) {
    throw new RoomFitError(
      "the room comes out inside out: the corners are not in the order of BOX_CORNER_SIGNS",
    );
  }
  const midX = (xLo + xHi) / 2;
  const midZ = (zLo + zHi) / 2;
  return Float64Array.from([
    radians(pitchDeg),
    radians(rollDeg),
    yaw,
    midX * cosYaw + midZ * sinYaw,
    -midX * sinYaw + midZ * cosYaw,
    depth,
    height,
    width,
  ]);
}

/** The parameter vector of a room (its centre's height is the floor's, not a parameter). */
function paramsOf({ pitchDeg, rollDeg, room }: RoomStart): Float64Array {
  const { center, size } = room;
  return Float64Array.from([
    radians(pitchDeg),
    radians(rollDeg),
    radians(room.yawDeg),
    center[0],
    center[2],
    size[0],
    size[1],
    size[2],
  ]);
}

/** The room box of a parameter vector, its yaw in degrees within (-180, 180]. */
function roomBox(params: Float64Array, cameraHeight: number): RoomBox {
  let yawDeg = degrees(at(params, 2));
  yawDeg -= 360 * Math.ceil((yawDeg - 180) / 360);
  const height = at(params, 6);
  return {
    center: [at(params, 3), height / 2 - cameraHeight, at(params, 4)],
    size: [at(params, 5), height, at(params, 7)],
    yawDeg,
  };
}

interface Evaluation {
  residuals: Float64Array; // 2n corner coordinates, then the unseen wall's if any
  jacobian: Float64Array; // rows x N_PARAMS, row-major
}

/** Residuals and their Jacobian; null if a known corner is behind the camera. */
function residualsAndJacobian(params: Float64Array, observations: Observations): Evaluation | null {
  const [pitch, roll, yaw, cx, cz, depth, height, width] = Array.from(params) as Params;
  const { K, indices, pixels } = observations;
  const n = indices.length;
  const rows = 2 * n + (observations.unseenWall === null ? 0 : 1);
  const residuals = new Float64Array(rows);
  const jacobian = new Float64Array(rows * N_PARAMS);
  const rotation = rotY(yaw);
  const cosYaw = Math.cos(yaw);
  const sinYaw = Math.sin(yaw);
  const dRotation: Mat3 = [
    [-sinYaw, 0, cosYaw],
    [0, 0, 0],
    [-cosYaw, 0, -sinYaw],
  ];
  const camFromWorld = transpose(worldFromCv(degrees(pitch), degrees(roll)));
  const center: Vec3 = [cx, height / 2 - observations.cameraHeight, cz];
  const camColumn = (j: number): Vec3 => [
    at(camFromWorld[0], j),
    at(camFromWorld[1], j),
    at(camFromWorld[2], j),
  ];
  const scaled = (v: Vec3, s: number): Vec3 => [v[0] * s, v[1] * s, v[2] * s];

  for (let k = 0; k < n; k++) {
    const signs = BOX_CORNER_SIGNS[at(indices, k)] as Vec3;
    const half: Vec3 = [(signs[0] * depth) / 2, (signs[1] * height) / 2, (signs[2] * width) / 2];
    const turned = matVec(rotation, half);
    const world: Vec3 = [turned[0] + center[0], turned[1] + center[1], turned[2] + center[2]];
    const cam = matVec(camFromWorld, world);
    if (cam[2] <= MIN_DEPTH) return null;
    const homogeneous = matVec(K, cam);
    const pixel: [number, number] = [
      homogeneous[0] / homogeneous[2],
      homogeneous[1] / homogeneous[2],
    ];
    const observed = pixels[k] as Point2;

    // d(camera point)/d(parameter), one column per parameter. Pitch turns the world point
    // about world z before the camera rotation; roll turns the camera point about the axis.
    const dCam: Vec3[] = [
      matVec(camFromWorld, [-world[1], world[0], 0]),
      [cam[1], -cam[0], 0],
      matVec(camFromWorld, matVec(dRotation, half)),
      camColumn(0),
      camColumn(2),
      matVec(camFromWorld, scaled([rotation[0][0], rotation[1][0], rotation[2][0]], signs[0] / 2)),
      scaled(camColumn(1), (1 + signs[1]) / 2),
      matVec(camFromWorld, scaled([rotation[0][2], rotation[1][2], rotation[2][2]], signs[2] / 2)),
    ];
    for (let axis = 0; axis < 2; axis++) {
      const row = 2 * k + axis;
      residuals[row] = at(pixel, axis) - at(observed, axis);
      // d(pixel)/d(camera point): (row of K - pixel * last row of K) / w.
      const kRow = K[axis] as Vec3;
      const dPixel: Vec3 = [0, 1, 2].map(
        (j) => (at(kRow, j) - at(pixel, axis) * at(K[2], j)) / homogeneous[2],
      ) as Vec3;
      for (let j = 0; j < N_PARAMS; j++)
        jacobian[row * N_PARAMS + j] = dot3(dPixel, dCam[j] as Vec3);
    }
  }
  const wall = observations.unseenWall;
  if (wall === null) return { residuals, jacobian };

  // The unseen wall's local coordinate (the centre's along the wall's axis, plus or minus half
  // the size) against side * unseenWallDistance, weighted by fx.
  const weight = at(K[0], 0);
  const wallRow = new Float64Array(N_PARAMS);
  let position: number;
  if (wall.axis === 0) {
    // local x = x cos(yaw) - z sin(yaw)
    wallRow.set([-cx * sinYaw - cz * cosYaw, cosYaw, -sinYaw, wall.side / 2], 2);
    position = cx * cosYaw - cz * sinYaw + (wall.side * depth) / 2;
  } else {
    // local z = x sin(yaw) + z cos(yaw)
    wallRow.set([cx * cosYaw - cz * sinYaw, sinYaw, cosYaw], 2);
    wallRow[7] = wall.side / 2;
    position = cx * sinYaw + cz * cosYaw + (wall.side * width) / 2;
  }
  residuals[2 * n] = weight * (position - wall.side * observations.unseenWallDistance);
  for (let j = 0; j < N_PARAMS; j++) jacobian[2 * n * N_PARAMS + j] = weight * at(wallRow, j);
  return { residuals, jacobian };
}

/** (J^T J, J^T r) of an evaluation. */
function normalEquations({ residuals, jacobian }: Evaluation): [Float64Array, Float64Array] {
  const normal = new Float64Array(N_PARAMS * N_PARAMS);
  const gradient = new Float64Array(N_PARAMS);
  for (let r = 0; r < residuals.length; r++) {
    const offset = r * N_PARAMS;
    for (let i = 0; i < N_PARAMS; i++) {
      const ji = at(jacobian, offset + i);
      gradient[i] = at(gradient, i) + ji * at(residuals, r);
      for (let j = 0; j < N_PARAMS; j++) {
        normal[i * N_PARAMS + j] = at(normal, i * N_PARAMS + j) + ji * at(jacobian, offset + j);
      }
    }
  }
  return [normal, gradient];
}

/** x with A x = b for a symmetric positive definite A (Cholesky); null if A is not. */
function solveSpd(a: Float64Array, b: Float64Array): Float64Array | null {
  const size = b.length;
  const lower = new Float64Array(size * size);
  for (let j = 0; j < size; j++) {
    for (let i = j; i < size; i++) {
      let sum = at(a, i * size + j);
      for (let k = 0; k < j; k++) sum -= at(lower, i * size + k) * at(lower, j * size + k);
      if (i === j) {
        if (!(sum > 0)) return null;
        lower[j * size + j] = Math.sqrt(sum);
      } else {
        lower[i * size + j] = sum / at(lower, j * size + j);
      }
    }
  }
  const x = Float64Array.from(b);
  for (let i = 0; i < size; i++) {
    for (let k = 0; k < i; k++) x[i] = at(x, i) - at(lower, i * size + k) * at(x, k);
    x[i] = at(x, i) / at(lower, i * size + i);
  }
  for (let i = size - 1; i >= 0; i--) {
    for (let k = i + 1; k < size; k++) x[i] = at(x, i) - at(lower, k * size + i) * at(x, k);
    x[i] = at(x, i) / at(lower, i * size + i);
  }
  return x;
}

const sumOfSquares = (values: Float64Array): number => values.reduce((sum, x) => sum + x * x, 0);

interface Minimum {
  params: Float64Array;
  residuals: Float64Array;
  trials: number;
  converged: boolean;
}

/** Minimise the squared residuals from `start`, or from `fallback` when `start` puts a known
 * corner behind the camera (steps 3-4 of room_fit.py's docstring). */
function levenbergMarquardt(
  observations: Observations,
  start: Float64Array,
  fallback: Float64Array | null = null,
): Minimum {
  let params = start;
  let evaluation = residualsAndJacobian(params, observations);
  if (evaluation === null && fallback !== null) {
    params = fallback; // the start puts a known corner behind the camera
    evaluation = residualsAndJacobian(params, observations);
  }
  if (evaluation === null) {
    throw new RoomFitError("the initial guess puts a known corner behind the camera");
  }
  let cost = sumOfSquares(evaluation.residuals);
  let [normal, gradient] = normalEquations(evaluation);
  let damping = LAMBDA_INIT;
  let growth = 2;
  const done = (trials: number, converged: boolean): Minimum => ({
    params,
    residuals: (evaluation as Evaluation).residuals,
    trials,
    converged,
  });
  for (let trial = 1; trial <= MAX_TRIALS; trial++) {
    const scale = new Float64Array(N_PARAMS);
    let largest = 0;
    for (let i = 0; i < N_PARAMS; i++) largest = Math.max(largest, at(normal, i * N_PARAMS + i));
    for (let i = 0; i < N_PARAMS; i++) {
      scale[i] = Math.max(at(normal, i * N_PARAMS + i), 1e-12 * largest); // keeps it regular
    }
    const damped = Float64Array.from(normal);
    for (let i = 0; i < N_PARAMS; i++) {
      damped[i * N_PARAMS + i] = at(damped, i * N_PARAMS + i) + damping * at(scale, i);
    }
    const step = solveSpd(
      damped,
      gradient.map((g) => -g),
    );
    if (step !== null) {
      const largestParam = params.reduce((m, p) => Math.max(m, Math.abs(p)), 0);
      const largestStep = step.reduce((m, s) => Math.max(m, Math.abs(s)), 0);
      if (largestStep <= STEP_TOLERANCE * (1 + largestParam)) return done(trial, true);
      const candidate = params.map((p, i) => p + at(step, i));
      const next = residualsAndJacobian(candidate, observations);
      if (next !== null) {
        const newCost = sumOfSquares(next.residuals);
        // Gain ratio: the actual decrease over the one the linear model predicts.
        let predicted = 0;
        for (let i = 0; i < N_PARAMS; i++) {
          predicted += at(step, i) * (damping * at(scale, i) * at(step, i) - at(gradient, i));
        }
        const gain = (cost - newCost) / predicted;
        if (gain > 0) {
          params = candidate;
          evaluation = next;
          cost = newCost;
          [normal, gradient] = normalEquations(next);
          damping *= Math.max(1 / 3, 1 - (2 * gain - 1) ** 3);
          growth = 2;
          continue;
        }
      }
    }
    damping *= growth;
    growth *= 2;
    if (damping > LAMBDA_MAX) return done(trial, true); // no step lowers the error: a minimum
  }
  return done(MAX_TRIALS, false);
}
