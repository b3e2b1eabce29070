// Where support arrows go in 3D: the TypeScript counterpart of the reviewer viewer's
// backend/src/holiscene/viewer/geometry.py (support_arrows), same rules and constants.
// An arrow runs from the supporter to the supported object (red: from below, blue: from
// behind). It starts at the supporter: an object's box centre; the floor under the object;
// the nearest wall point at the object's height; the ceiling above it. It passes through the
// object and sticks out on its far side, so the head is not hidden inside the mesh.
import type { SceneObject } from "@holiscene/schema";
import { boxCorners } from "../../geometry/boxes";
import { dot3, sub3, type Vec3 } from "../../geometry/camera";

export const ARROW_OVERSHOOT = 0.2;
export const MIN_ARROW_LENGTH = 0.4;
export const WALL_FALLBACK_DISTANCE = 0.4;
const STRUCTURAL = new Set(["floor", "wall", "ceiling"]);

export interface ArrowSupport {
  child: string;
  parent: string;
  type: "below" | "behind";
}

export interface Arrow3d extends ArrowSupport {
  start: Vec3;
  end: Vec3;
}

/** The room as the arrows need it: its 8 corners (contract order), or only the floor's y. */
export interface ArrowRoom {
  corners: readonly Vec3[] | null;
  floorY: number | null;
}

const add = (a: Vec3, b: Vec3): Vec3 => [a[0] + b[0], a[1] + b[1], a[2] + b[2]];
const scale = (a: Vec3, s: number): Vec3 => [a[0] * s, a[1] * s, a[2] * s];
const length = (a: Vec3) => Math.hypot(...a);

/** The object's 8 box corners, from corners_3d or else box_3d; null when it has no box. */
export function objectCorners(object: SceneObject): Vec3[] | null {
  if (object.corners_3d) return object.corners_3d.map((c) => [c[0], c[1], c[2]] as Vec3);
  const box = object.box_3d;
  if (!box) return null;
  const v = (p: number[]): Vec3 => [p[0] ?? 0, p[1] ?? 0, p[2] ?? 0];
  return boxCorners(v(box.center), v(box.size), box.yaw_deg);
}

export function centreOf(points: readonly Vec3[]): Vec3 {
  const sum = points.reduce((s, p) => add(s, p), [0, 0, 0] as Vec3);
  return scale(sum, 1 / points.length);
}

/** The point of the room's four walls nearest to `point`, at the point's height. */
export function nearestWallPoint(room: readonly Vec3[], point: Vec3): Vec3 {
  let best: Vec3 = point;
  let bestDistance = Number.POSITIVE_INFINITY;
  for (let i = 0; i < 4; i++) {
    const a = room[i] as Vec3;
    const b = room[(i + 1) % 4] as Vec3;
    const ex = b[0] - a[0];
    const ez = b[2] - a[2];
    const t = Math.min(
      1,
      Math.max(
        0,
        ((point[0] - a[0]) * ex + (point[2] - a[2]) * ez) / Math.max(ex * ex + ez * ez, 1e-12),
      ),
    );
    const q: Vec3 = [a[0] + t * ex, point[1], a[2] + t * ez];
    const distance = Math.hypot(point[0] - q[0], point[2] - q[2]);
    if (distance < bestDistance) {
      bestDistance = distance;
      best = q;
    }
  }
  return best;
}

function structuralAnchor(parent: string, room: ArrowRoom, centre: Vec3): Vec3 | null {
  const corners = room.corners;
  const meanY = (from: number) =>
    corners ? corners.slice(from, from + 4).reduce((s, c) => s + c[1], 0) / 4 : null;
  if (parent === "floor") {
    const y = corners ? meanY(0) : room.floorY;
    return y === null ? null : [centre[0], y, centre[2]];
  }
  if (parent === "ceiling") {
    const y = meanY(4);
    return y === null ? null : [centre[0], y, centre[2]];
  }
  if (corners) return nearestWallPoint(corners, centre);
  // No room: the wall is behind the object as seen from the camera (the origin).
  const away: Vec3 = [centre[0], 0, centre[2]];
  const norm = length(away);
  return norm < 1e-9 ? null : add(centre, scale(away, WALL_FALLBACK_DISTANCE / norm));
}

/** One arrow per support whose object and supporter have a place in 3D. */
export function planArrows(
  objects: readonly SceneObject[],
  supports: Iterable<ArrowSupport>,
  room: ArrowRoom,
): Arrow3d[] {
  const corners = new Map<string, Vec3[]>();
  for (const object of objects) {
    const c = objectCorners(object);
    if (c) corners.set(object.id, c);
  }
  const arrows: Arrow3d[] = [];
  for (const support of supports) {
    const child = corners.get(support.child);
    if (!child) continue;
    const centre = centreOf(child);
    const supporter = corners.get(support.parent);
    let start = STRUCTURAL.has(support.parent)
      ? structuralAnchor(support.parent, room, centre)
      : supporter && centreOf(supporter);
    if (!start) continue; // the supporter has no place in 3D (no room, or no box)
    const offset = sub3(centre, start);
    const distance = length(offset);
    const direction: Vec3 = distance > 1e-6 ? scale(offset, 1 / distance) : [0, 1, 0];
    const reach = Math.max(...child.map((p) => dot3(sub3(p, centre), direction)));
    const end = add(centre, scale(direction, reach + ARROW_OVERSHOOT));
    if (length(sub3(end, start)) < MIN_ARROW_LENGTH)
      start = sub3(end, scale(direction, MIN_ARROW_LENGTH));
    arrows.push({ child: support.child, parent: support.parent, type: support.type, start, end });
  }
  return arrows;
}
