// Floor, wall and ceiling tags: those of one supporter side by side become one tag.

import type { SceneObject } from "@holiscene/schema";
import { describe, expect, it } from "vitest";
import type { SupporterShape } from "./arrowGeometry";
import { arrowFeet, sharedTags } from "./arrowLayer";

const half = [20, 6] as const;

describe("sharedTags", () => {
  it("joins a row of wall tags into one at their mean, and keeps other supporters apart", () => {
    const tags = sharedTags([
      { id: "book1", parent: "wall", at: [100, 50], half },
      { id: "book2", parent: "wall", at: [130, 52], half },
      { id: "book3", parent: "wall", at: [160, 54], half },
      { id: "chair", parent: "floor", at: [130, 52], half },
      { id: "frame", parent: "wall", at: [400, 50], half },
    ]);
    expect(tags.map((t) => t.ids)).toEqual([["book1", "book2", "book3"], ["chair"], ["frame"]]);
    expect(tags[0]?.at[0]).toBeCloseTo(130);
    expect(tags[0]?.at[1]).toBeCloseTo(52);
  });

  it("keeps tags one above the other apart once they are farther than two tag heights", () => {
    const tags = sharedTags([
      { id: "top", parent: "wall", at: [100, 50], half },
      { id: "low", parent: "wall", at: [100, 80], half },
    ]);
    expect(tags).toHaveLength(2);
  });
});

describe("arrowFeet", () => {
  const object = (id: string, bbox: [number, number, number, number]) =>
    ({ id, class: "lamp", bbox }) as unknown as SceneObject;
  const shape = (bbox: [number, number, number, number]): SupporterShape => ({
    bbox,
    mask: null,
    centroid: [(bbox[0] + bbox[2]) / 2, (bbox[1] + bbox[3]) / 2],
  });

  it("moves aside the arrows of children one above the other on one supporter", () => {
    const table = shape([0, 100, 200, 160]);
    const lamp = object("lamp", [90, 40, 110, 100]);
    const shade = object("shade", [90, 10, 110, 40]);
    const book = object("book", [20, 80, 40, 100]);
    const supporters = new Map([
      ["table", table],
      ["lamp", shape([90, 40, 110, 100])],
      ["shade", shape([90, 10, 110, 40])],
      ["book", shape([20, 80, 40, 100])],
    ]);
    const onTable = { parent: "table", type: "below" };
    const feet = arrowFeet(
      [
        { object: lamp, edge: onTable },
        { object: shade, edge: onTable },
        { object: book, edge: onTable },
      ],
      supporters,
      2,
    );
    expect(feet.get("lamp")).toEqual([100, 100]);
    expect(feet.get("shade")).toEqual([108, 100]); // one step of 4 widths to the right
    expect(feet.get("book")).toEqual([30, 106]); // apart from both: under it (at least 8 widths long)
  });
});
