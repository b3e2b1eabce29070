// Oriented 3D boxes: the TypeScript twin of backend/src/holiscene/geometry/boxes.py.
import { matVec, radians, rotY, type Vec3 } from "./camera";

/**
 * Corner order of every 3D box (the contract's BOX_CORNER_SIGNS, holiscene_schema/scene.py):
 * signs of the local x, y, z half-sizes, bottom face first. The room-fit vectors carry a copy
 * that the tests compare with this one.
 */
export const BOX_CORNER_SIGNS: readonly Vec3[] = [
  [-1, -1, -1],
  [1, -1, -1],
  [1, -1, 1],
  [-1, -1, 1],
  [-1, 1, -1],
  [1, 1, -1],
  [1, 1, 1],
  [-1, 1, 1],
];

/** The 8 world corners of a box with local size (front, up, right) and yaw about +y. */
export function boxCorners(center: Vec3, size: Vec3, yawDeg: number): Vec3[] {
  const rotation = rotY(radians(yawDeg));
  return BOX_CORNER_SIGNS.map((signs) => {
    const local: Vec3 = [
      (signs[0] * size[0]) / 2,
      (signs[1] * size[1]) / 2,
      (signs[2] * size[2]) / 2,
    ];
    const turned = matVec(rotation, local);
    return [turned[0] + center[0], turned[1] + center[1], turned[2] + center[2]];
  });
}
