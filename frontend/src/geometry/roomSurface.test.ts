import { describe, expect, it } from "vitest";
import { roomSurfaceAt } from "./roomSurface";

// A 6 x 2.8 x 5 m room (x forward, y up, z right), the camera 1.4 m above its floor, 1 m
// from its back wall and 2 m from its left one, looking level along +x; a 640 x 480 photo.
const floorY = -1.4;
const ceilingY = 1.4;
const plan: [number, number][] = [
  [-1, -2],
  [5, -2],
  [5, 3],
  [-1, 3],
];
const corners = [
  ...plan.map(([x, z]) => [x, floorY, z]),
  ...plan.map(([x, z]) => [x, ceilingY, z]),
];
const camera = {
  K: [
    [500, 0, 320],
    [0, 500, 240],
    [0, 0, 1],
  ],
  pitch_deg: 0,
  roll_deg: 0,
};

describe("roomSurfaceAt", () => {
  it("finds the floor low in the photo, the ceiling high, a wall ahead", () => {
    expect(roomSurfaceAt([320, 470], camera, corners)).toBe("floor");
    expect(roomSurfaceAt([320, 10], camera, corners)).toBe("ceiling");
    expect(roomSurfaceAt([320, 240], camera, corners)).toBe("wall");
    // Far to the left, at the camera's height: the left wall.
    expect(roomSurfaceAt([5, 240], camera, corners)).toBe("wall");
  });

  it("follows the pitch: looking down, the photo's middle shows the floor", () => {
    const down = { ...camera, pitch_deg: 30 };
    expect(roomSurfaceAt([320, 240], down, corners)).toBe("floor");
    // The front wall is 5 m away: looking level at 20 px below the centre is still the wall.
    expect(roomSurfaceAt([320, 260], camera, corners)).toBe("wall");
  });

  it("says nothing without a pose, without a room, or with the camera outside it", () => {
    expect(roomSurfaceAt([320, 470], { ...camera, pitch_deg: null }, corners)).toBeNull();
    expect(roomSurfaceAt([320, 470], camera, null)).toBeNull();
    const elsewhere = corners.map(([x, y, z]) => [(x ?? 0) + 10, y ?? 0, z ?? 0]);
    expect(roomSurfaceAt([320, 470], camera, elsewhere)).toBeNull();
  });
});
