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

/**
 * The surface of the room (8 corners, contract order: floor 0-3, then ceiling 4-7, in the
 * world frame with the camera at the origin) seen at `pixel`; null without a room or a
 * camera pose, or when the camera is not inside the room (a layout too wrong to say).
 */
export function roomSurfaceAt(
  pixel: Point2,
  camera: SurfaceCamera | null | undefined,
  corners: readonly (readonly number[])[] | null | undefined,
): RoomSurface | null {
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
  const direction = axes.map((axis) => dot3(ray, axis));
  // The face the ray leaves through: the nearest of the three it heads for.
  let exit = { t: Number.POSITIVE_INFINITY, axis: -1, up: false };
  direction.forEach((d, i) => {
    if (Math.abs(d) < 1e-12) return;
    const wall = d > 0 ? (extents[i] as number) : 0;
    const t = (wall - (origin[i] as number)) / d;
    if (t > 0 && t < exit.t) exit = { t, axis: i, up: d > 0 };
  });
  if (exit.axis === -1) return null;
  if (exit.axis !== 1) return "wall";
  return exit.up ? "ceiling" : "floor";
}
