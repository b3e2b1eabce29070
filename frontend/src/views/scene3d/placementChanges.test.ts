// What the 3D panel's notice counts: objects added (or never placed), removed, changed in
// class, box or mask since the placement; and telling a placement's revision from an edit's.
import type { SceneObject } from "@holiscene/schema";
import { describe, expect, it } from "vitest";
import { changesSincePlacement, describeChanges, newlyPlaced } from "./placementChanges";

const box3d = (x: number) => ({ center: [x, 0, 2], size: [1, 1, 1], yaw_deg: 0 });

function object(id: string, extra: Partial<SceneObject> = {}): SceneObject {
  return {
    id,
    class: "chair",
    bbox: [10, 10, 50, 60],
    box_3d: box3d(1),
    ...extra,
  } as unknown as SceneObject;
}

const placed = [object("a"), object("b"), object("c"), object("floor_1", { class: "floor" })];

describe("changes since placement", () => {
  it("are none right after the placement", () => {
    expect(changesSincePlacement(placed, placed)).toEqual({ added: [], removed: [], changed: [] });
  });

  it("count objects added, removed and changed in class, box or mask", () => {
    const current = [
      object("a", { class: "table" }),
      object("c", { bbox: [12, 10, 50, 60] }),
      object("d", { box_3d: null }),
    ];
    const changes = changesSincePlacement(placed, current);
    expect(changes).toEqual({ added: ["d"], removed: ["b"], changed: ["a", "c"] });
    expect(describeChanges(changes)).toBe("1 object added, 1 removed, 2 changed");
  });

  it("ignore room structure; count an object a person added without a 3D box as added", () => {
    const drawn = object("b2", { box_3d: null, set_by_person: ["object"] });
    const unplacedByPipeline = object("b3", { box_3d: null });
    const loaded = [...placed, drawn, unplacedByPipeline];
    expect(changesSincePlacement(loaded, loaded).added).toEqual(["b2"]);
    // Unless `loaded` is a run's result: it tried b2 and could not place it, and placing it
    // again would not either (the notice would never go away).
    expect(changesSincePlacement(loaded, loaded, true).added).toEqual([]);
    const redrawn = { ...drawn, bbox: [12, 10, 50, 60] } as SceneObject;
    expect(changesSincePlacement(loaded, [...placed, redrawn], true).changed).toEqual(["b2"]);
    const noStructure = placed.filter((o) => o.class !== "floor");
    expect(changesSincePlacement(placed, noStructure).removed).toEqual([]);
  });

  it("tell a placement's revision (new 3D boxes) from an object edit's", () => {
    const edited = [object("a", { class: "table" }), object("b"), object("d", { box_3d: null })];
    expect(newlyPlaced(placed, edited)).toBe(false);
    const replaced = edited.map((o) => ({ ...o, box_3d: box3d(2) }) as SceneObject);
    expect(newlyPlaced(edited, replaced)).toBe(true);
  });
});
