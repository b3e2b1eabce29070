// Which of the room's surfaces (floor, a wall, the ceiling) a pixel of the photo shows: the
// ray through the pixel, from the camera inside the room, leaves the room's cuboid through
// one face. An arrow dropped on the floor between objects then makes the floor its supporter.
import {
  dot3,
  invert,
  type Matrix3Like,
  matVec,
  type Point2,
  sub3,
  type Vec3,
  worldFromCv,
} from "./camera";

export type RoomSurface = "floor" | "wall" | "ceiling";

export interface SurfaceCamera {
  K: Matrix3Like;
  pitch_deg: number | null;
  roll_deg: number | null;
}

const unit = (v: Vec3): Vec3 => {
  const length = Math.hypot(...v);
  return [v[0] / length, v[1] / length, v[2] / length];
};

/** How far along the ray through a pixel it leaves the room through each kind of face (in
 * the ray's units; null for one it does not head for). */
export interface RoomExits {
  floor: number | null;
  wall: number | null;
  ceiling: number | null;
}

/**
 * Where the ray through `pixel` leaves the room (8 corners, contract order: floor 0-3, then
 * ceiling 4-7, in the world frame with the camera at the origin): the distance to the floor
 * or ceiling it heads for and to the nearest wall it heads for. Null without a room or a
 * camera pose, or when the camera is not inside the room (a layout too wrong to say).
 */
export function roomExits(
  pixel: Point2,
  camera: SurfaceCamera | null | undefined,
  corners: readonly (readonly number[])[] | null | undefined,
): RoomExits | null {
  if (!camera || camera.pitch_deg == null || camera.roll_deg == null) return null;
  if (corners?.length !== 8) return null;
  const at = (i: number) => corners[i] as readonly number[];
  // The room's own axes: along its walls from corner 0, and up.
  const along = sub3(at(1), at(0));
  const across = sub3(at(3), at(0));
  const mean = (from: number, to: number) =>
    corners.slice(from, to).reduce((sum, c) => sum + (c[1] ?? 0), 0) / (to - from);
  const floorY = mean(0, 4);
  const extents = [Math.hypot(...along), mean(4, 8) - floorY, Math.hypot(...across)];
  if (extents.some((e) => !(e > 0))) return null;
  const axes = [unit(along), [0, 1, 0] as Vec3, unit(across)];
  // The camera (the world's origin) in the room's frame: from corner 0, and above the floor.
  const fromCorner = sub3([0, 0, 0], at(0));
  const origin = [dot3(fromCorner, axes[0] as Vec3), -floorY, dot3(fromCorner, axes[2] as Vec3)];
  if (origin.some((o, i) => o <= 0 || o >= (extents[i] as number))) return null;
  const rayCv = matVec(invert(camera.K), [pixel[0], pixel[1], 1]);
  const ray = matVec(worldFromCv(camera.pitch_deg, camera.roll_deg), rayCv);
  const exits: RoomExits = { floor: null, wall: null, ceiling: null };
  axes.forEach((axis, i) => {
    const d = dot3(ray, axis);
    if (Math.abs(d) < 1e-12) return;
    const t = ((d > 0 ? (extents[i] as number) : 0) - (origin[i] as number)) / d;
    if (!(t > 0)) return;
    if (i !== 1) exits.wall = Math.min(exits.wall ?? t, t);
    else if (d > 0) exits.ceiling = t;
    else exits.floor = t;
  });
  return exits;
}

/** The surface of the room seen at `pixel` (the face the ray leaves through first); null as
 * for `roomExits`. */
export function roomSurfaceAt(
  pixel: Point2,
  camera: SurfaceCamera | null | undefined,
  corners: readonly (readonly number[])[] | null | undefined,
): RoomSurface | null {
  const exits = roomExits(pixel, camera, corners);
  if (!exits) return null;
  const first = (["wall", "floor", "ceiling"] as const)
    .filter((face) => exits[face] !== null)
    .sort((a, b) => (exits[a] as number) - (exits[b] as number))[0];
  return first ?? null;
}
