// Support arrows in 3D start on the supporter and stick out beyond the supported object.
import type { SceneObject } from "@holiscene/schema";
import { describe, expect, it } from "vitest";
import { boxCorners } from "../../geometry/boxes";
import type { Vec3 } from "../../geometry/camera";
import { ARROW_OVERSHOOT, MIN_ARROW_LENGTH, planArrows } from "./arrowPlan";

const object = (id: string, center: Vec3, size: Vec3, yaw = 0): SceneObject =>
  ({
    id,
    class: "table",
    bbox: [0, 0, 1, 1],
    box_3d: { center, size, yaw_deg: yaw },
  }) as SceneObject;

// Floor at y = -1.5; walls at x = -1 and 4, z = -2 and 2.
const ROOM = boxCorners([1.5, -0.2, 0], [5, 2.6, 4], 0);
const room = { corners: ROOM, floorY: null };

describe("planArrows", () => {
  it("runs from the floor under an object up through it", () => {
    const table = object("t", [3, -1.1, 0.5], [1, 0.8, 1]);
    const [arrow] = planArrows([table], [{ child: "t", parent: "floor", type: "below" }], room);
    expect(arrow?.start).toEqual([3, expect.closeTo(-1.5, 9), 0.5]);
    // Up through the top (y = -0.7) and the overshoot beyond it.
    expect(arrow?.end[1]).toBeCloseTo(-0.7 + ARROW_OVERSHOOT, 9);
    expect(arrow?.end[0]).toBeCloseTo(3, 9);
  });

  it("runs from a supporting object's centre, and from the nearest wall", () => {
    const table = object("t", [3, -1.1, 0.5], [1, 0.8, 1]);
    const lamp = object("l", [3, -0.5, 0.5], [0.2, 0.4, 0.2]);
    const picture = object("p", [3.95, 0.2, -1], [0.05, 0.5, 0.7]);
    const arrows = planArrows(
      [table, lamp, picture],
      [
        { child: "l", parent: "t", type: "below" },
        { child: "p", parent: "wall", type: "behind" },
      ],
      room,
    );
    expect(arrows.map((a) => [a.child, a.type])).toEqual([
      ["l", "below"],
      ["p", "behind"],
    ]);
    for (const [i, v] of (arrows[0]?.start ?? []).entries()) {
      expect(v).toBeCloseTo([3, -1.1, 0.5][i] ?? 0, 9);
    }
    // The picture hangs on the x = 4 wall: its arrow starts there, at its height, and points
    // into the room, at least MIN_ARROW_LENGTH long.
    const wall = arrows[1];
    expect(wall?.start[1]).toBeCloseTo(0.2, 9);
    expect(wall?.start[2]).toBeCloseTo(-1, 9);
    expect(wall?.end[0]).toBeLessThan(3.95);
    const length = Math.hypot(...(wall?.end ?? [0, 0, 0]).map((v, i) => v - (wall?.start[i] ?? 0)));
    expect(length).toBeGreaterThanOrEqual(MIN_ARROW_LENGTH - 1e-9);
  });

  it("leaves out arrows whose object or supporter has no place in 3D", () => {
    const table = object("t", [3, -1.1, 0.5], [1, 0.8, 1]);
    const boxless = { id: "b", class: "box", bbox: [0, 0, 1, 1] } as SceneObject;
    const arrows = planArrows(
      [table, boxless],
      [
        { child: "b", parent: "floor", type: "below" },
        { child: "t", parent: "b", type: "below" },
        { child: "t", parent: "ceiling", type: "below" },
      ],
      { corners: null, floorY: -1.5 },
    );
    expect(arrows).toEqual([]);
  });
});
