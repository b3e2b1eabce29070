import { describe, expect, it } from "vitest";
import { rectsOverlap } from "../../photo/labelPlacement";
import { placeTags, type TagRequest } from "./offerLabelPlacement";

const bounds = { left: -20, top: -20, right: 520, bottom: 420 };
const tag = (box: [number, number, number, number]): TagRequest => ({ box, width: 60, height: 14 });

describe("suggested boxes' tags", () => {
  it("go above their box's top-left corner when nothing is there", () => {
    const [rect] = placeTags([tag([100, 100, 200, 180])], [0], bounds, []);
    expect(rect).toEqual({ left: 100, top: 86, right: 160, bottom: 100 });
  });

  it("of boxes sharing a corner do not cover each other, the surer one keeping the first spot", () => {
    // A table and, nearly on it, an otherprop box: both would take the same spot.
    const requests = [tag([100, 100, 260, 200]), tag([102, 101, 250, 190])];
    const rects = placeTags(requests, [1, 0], bounds, []);
    expect(rects[1]).toEqual({ left: 102, top: 87, right: 162, bottom: 101 });
    expect(rectsOverlap(rects[0] as never, rects[1] as never)).toBe(false);
  });

  it("keep clear of the objects' own labels, and stay inside the bounds", () => {
    const objectLabel = { left: 95, top: 80, right: 170, bottom: 100 };
    const [rect] = placeTags([tag([100, 100, 300, 200])], [0], bounds, [objectLabel]);
    expect(rectsOverlap(rect as never, objectLabel)).toBe(false);
    const [edge] = placeTags([tag([490, -20, 520, 30])], [0], bounds, []);
    expect(edge?.right).toBeLessThanOrEqual(bounds.right);
    expect(edge?.top).toBeGreaterThanOrEqual(bounds.top);
  });

  it("take the least covered spot when every spot is taken", () => {
    const everything = [{ left: -20, top: -20, right: 520, bottom: 420 }];
    const rects = placeTags([tag([100, 100, 200, 200])], [0], bounds, everything);
    expect(rects[0]).toEqual({ left: 100, top: 86, right: 160, bottom: 100 });
  });

  it("leave out a tag that may go without one where every spot is taken", () => {
    const everything = [{ left: -20, top: -20, right: 520, bottom: 420 }];
    const box = tag([100, 100, 200, 200]);
    expect(placeTags([box], [0], bounds, everything, () => true)).toEqual([null]);
    expect(placeTags([box], [0], bounds, everything, () => false)[0]).not.toBeNull();
    // With a free spot it keeps its tag.
    expect(placeTags([box], [0], bounds, [], () => true)[0]).not.toBeNull();
  });
});
