// The room the layout editor starts from: its back corners on the photo, its floor at the
// camera's height, and the room fit reads it back from those corners.
import { describe, expect, it } from "vitest";
import { K } from "../testing/roomScene";
import type { Point2 } from "./camera";
import { fitRoom } from "./roomFit";
import { STARTER_FRONT_WALL_M, starterRoom } from "./starterRoom";

const onPhoto = (p: Point2 | null, width: number, height: number) =>
  p !== null && p[0] >= 0 && p[0] <= width && p[1] >= 0 && p[1] <= height;

describe("starterRoom", () => {
  it.each([
    [0, 0],
    [-15, 4],
    [12, -5],
  ])("puts the back wall's corners on the photo at pitch %d, roll %d", (pitch, roll) => {
    const start = starterRoom(K, 640, 480, 1.5, pitch, roll);
    const known = start.corners2d.flatMap((p, i) => (p ? [i] : []));
    expect(known).toEqual([1, 2, 5, 6]);
    for (const i of known) expect(onPhoto(start.corners2d[i] ?? null, 640, 480)).toBe(true);
    expect(start.room.center[1] - start.room.size[1] / 2).toBeCloseTo(-1.5, 9); // the floor
    expect(start.room.center[0] - start.room.size[0] / 2).toBeCloseTo(-STARTER_FRONT_WALL_M, 9);
  });

  it("is read back by the room fit from its corners", () => {
    const start = starterRoom(K, 640, 480, 1.4, 5, 2);
    const fit = fitRoom(K, start.corners2d, 1.4, { unseenWallDistance: STARTER_FRONT_WALL_M });
    expect(fit.pitchDeg).toBeCloseTo(5, 4);
    expect(fit.rollDeg).toBeCloseTo(2, 4);
    fit.room.size.forEach((side, i) => {
      expect(side).toBeCloseTo(start.room.size[i] ?? Number.NaN, 4);
    });
  });

  it("makes the room taller than a high camera", () => {
    const start = starterRoom(K, 640, 480, 2.5);
    expect(start.room.size[1]).toBeCloseTo(3, 9);
  });
});
