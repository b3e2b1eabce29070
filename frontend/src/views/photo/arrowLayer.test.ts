// Floor, wall and ceiling tags: those of one supporter side by side become one tag.
import { describe, expect, it } from "vitest";
import { sharedTags } from "./arrowLayer";

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
