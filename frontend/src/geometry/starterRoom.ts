// A room for the layout editor to start from when the scene has none (the pipeline found too
// few lines, or it has not run): the camera level, or at the scene's pitch and roll when they
// are known, looking at the back wall of a plain box room whose four back corners sit well
// inside the photo. The annotator drags those corners onto the room's; nothing of it is saved
// until a corner moves.
import { boxCorners } from "./boxes";
import { type Matrix3Like, type Point2, projectPoints, type Vec3 } from "./camera";
import type { RoomBox } from "./roomFit";

/** The wall behind the photographer, metres behind the camera (it is out of view). */
export const STARTER_FRONT_WALL_M = 1;
/** The starter room's height, metres (taller when the camera is higher). */
const STARTER_ROOM_HEIGHT_M = 2.6;
/** The share of the photo (each way, about its centre) the back wall fills at first. */
const BACK_WALL_SHARE = 0.6;
/** The back wall is pushed back by this factor until its corners are on the photo. */
const STEP_BACK = 1.25;
const MAX_STEPS = 20;
/** The back wall's corners, in the contract's corner order (the box's +x face). */
const BACK_CORNERS: readonly number[] = [1, 2, 5, 6];

export interface StarterRoom {
  pitchDeg: number;
  rollDeg: number;
  room: RoomBox;
  corners3d: Vec3[];
  /** The corners in the photo: the back wall's four, null for the front wall's (behind). */
  corners2d: (Point2 | null)[];
}

/**
 * The starter room for a photo of `width` x `height` pixels with intrinsics `K`, the camera
 * `cameraHeight` metres above the floor. Corners 1, 2, 5, 6 are the back wall's (the box's
 * +x face, the camera looks along +x); the front wall is STARTER_FRONT_WALL_M behind.
 */
export function starterRoom(
  K: Matrix3Like,
  width: number,
  height: number,
  cameraHeight: number,
  pitchDeg = 0,
  rollDeg = 0,
): StarterRoom {
  const fx = K[0]?.[0] ?? 1;
  const fy = K[1]?.[1] ?? 1;
  const roomHeight = Math.max(STARTER_ROOM_HEIGHT_M, cameraHeight + 0.5);
  // Level camera: the floor's and the ceiling's back edges at BACK_WALL_SHARE of half the
  // photo's height from its centre, the side walls likewise across.
  const reach = Math.max(cameraHeight, roomHeight - cameraHeight);
  let back = (reach * fy) / ((BACK_WALL_SHARE * height) / 2);
  const halfWidthAt = (distance: number) => (BACK_WALL_SHARE * distance * width) / 2 / fx;
  const make = (distance: number) => {
    const depth = distance + STARTER_FRONT_WALL_M;
    const size: Vec3 = [depth, roomHeight, 2 * halfWidthAt(distance)];
    const center: Vec3 = [distance - depth / 2, roomHeight / 2 - cameraHeight, 0];
    const corners3d = boxCorners(center, size, 0);
    const corners2d = projectPoints(K, pitchDeg, rollDeg, corners3d);
    return { room: { center, size, yawDeg: 0 }, corners3d, corners2d };
  };
  const onPhoto = (p: Point2 | null) =>
    p !== null && p[0] >= 0 && p[0] <= width && p[1] >= 0 && p[1] <= height;
  const backInView = (corners: (Point2 | null)[]) =>
    BACK_CORNERS.every((i) => onPhoto(corners[i] ?? null));
  let room = make(back);
  // A tilted camera may see the back wall off centre: step back until its corners are in
  // (a camera tilted past half its field of view never sees them all; the room stays as is).
  for (let step = 0; step < MAX_STEPS && !backInView(room.corners2d); step++) {
    back *= STEP_BACK;
    room = make(back);
  }
  const corners2d = room.corners2d.map((p, i) => (BACK_CORNERS.includes(i) ? p : null));
  return { pitchDeg, rollDeg, room: room.room, corners3d: room.corners3d, corners2d };
}
