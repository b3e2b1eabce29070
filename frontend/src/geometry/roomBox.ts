// The room cuboid as the layout editor needs it: the box of stored corners, the distance of a
// wall the known corners leave unplaced, and the box's edges as image segments.

import {
  degrees,
  type Matrix3Like,
  matVec,
  type Point2,
  sub3,
  transpose,
  type Vec3,
  worldFromCv,
} from "./camera";
import type { RoomBox } from "./roomFit";

/** The 12 edges of a box by corner index (contract order: bottom face, then top face). */
export const BOX_EDGES: readonly (readonly [number, number])[] = [
  [0, 1],
  [1, 2],
  [2, 3],
  [3, 0],
  [4, 5],
  [5, 6],
  [6, 7],
  [7, 4],
  [0, 4],
  [1, 5],
  [2, 6],
  [3, 7],
];

/** Points closer to the camera plane than this (metres) are cut off before projecting. */
const NEAR = 0.05;

/**
 * The box with these 8 corners (contract order), as backend placement/room.py's
 * Room.from_corners reads it: local +x runs from corner 0 to 1, +z from 0 to 3.
 */
export function roomBoxFromCorners(corners: readonly Vec3[]): RoomBox {
  const c = (i: number) => corners[i] as Vec3;
  const xAxis = sub3(c(1), c(0));
  const zAxis = sub3(c(3), c(0));
  const mean = (axis: 0 | 1 | 2, from: number, to: number) =>
    corners.slice(from, to).reduce((sum, p) => sum + p[axis], 0) / (to - from);
  return {
    center: [mean(0, 0, 8), mean(1, 0, 8), mean(2, 0, 8)],
    size: [Math.hypot(...xAxis), mean(1, 4, 8) - mean(1, 0, 4), Math.hypot(...zAxis)],
    yawDeg: degrees(Math.atan2(-xAxis[2], xAxis[0])),
  };
}

/** A wall of the room: its axis in the plan (0 = the box's x, 1 = its z) and side. */
export interface WallSide {
  axis: 0 | 1;
  side: -1 | 1;
}

// The vertical room edges (corner i below, i + 4 above) on each wall, as in room_fit.py.
const WALL_EDGES: readonly (WallSide & { edges: readonly [number, number] })[] = [
  { axis: 0, side: -1, edges: [0, 3] },
  { axis: 0, side: 1, edges: [1, 2] },
  { axis: 1, side: -1, edges: [0, 1] },
  { axis: 1, side: 1, edges: [2, 3] },
];

/** The wall on which none of the known corners lies (the fit needs its distance), or null. */
export function unseenWall(corners2d: readonly (readonly number[] | null)[]): WallSide | null {
  const known = (i: number) => corners2d[i] != null || corners2d[i + 4] != null;
  const wall = WALL_EDGES.find((w) => !w.edges.some(known));
  return wall ? { axis: wall.axis, side: wall.side } : null;
}

/** Distance from the camera (the origin) to a wall of the box, along the box's own axis. */
export function wallDistance(room: RoomBox, wall: WallSide): number {
  const yaw = (room.yawDeg * Math.PI) / 180;
  const [x, , z] = room.center;
  // The centre in the box's own axes: local x = x cos(yaw) - z sin(yaw), z = x sin + z cos.
  const local =
    wall.axis === 0 ? x * Math.cos(yaw) - z * Math.sin(yaw) : x * Math.sin(yaw) + z * Math.cos(yaw);
  const half = (wall.axis === 0 ? room.size[0] : room.size[2]) / 2;
  return wall.side * (local + wall.side * half);
}

/**
 * The box's edges in the image: each edge is cut where it passes behind the camera, so edges
 * running out of view behind the photographer still show their visible part.
 */
export function projectBoxEdges(
  K: Matrix3Like,
  pitchDeg: number,
  rollDeg: number,
  corners: readonly Vec3[],
): [Point2, Point2][] {
  const camFromWorld = transpose(worldFromCv(pitchDeg, rollDeg));
  const cam = corners.map((p) => matVec(camFromWorld, p));
  const pixel = (p: Vec3): Point2 => {
    const [x, y, w] = matVec(K, p);
    return [x / w, y / w];
  };
  const segments: [Point2, Point2][] = [];
  for (const [i, j] of BOX_EDGES) {
    let a = cam[i] as Vec3;
    let b = cam[j] as Vec3;
    if (a[2] < NEAR && b[2] < NEAR) continue;
    // Cut the part in front of the near plane (z = NEAR in camera coordinates).
    const cut = (p: Vec3, q: Vec3): Vec3 => {
      const t = (NEAR - p[2]) / (q[2] - p[2]);
      return [p[0] + t * (q[0] - p[0]), p[1] + t * (q[1] - p[1]), NEAR];
    };
    if (a[2] < NEAR) a = cut(a, b);
    else if (b[2] < NEAR) b = cut(b, a);
    segments.push([pixel(a), pixel(b)]);
  }
  return segments;
}
