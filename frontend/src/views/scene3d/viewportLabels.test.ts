import { describe, expect, it } from "vitest";
import { type LabelCandidate, placeLabels } from "./viewportLabels";

const at = (id: string, x: number, y: number, size: number, wanted = false): LabelCandidate => ({
  id,
  x,
  y,
  size,
  wanted,
});

describe("placeLabels", () => {
  it("puts each tag's bottom centre on its object's anchor", () => {
    const [placed] = placeLabels([at("o3", 100, 60, 2)], 400, 300);
    // "o3": 2 characters of 7.5 px plus 22 px of swatch and padding, 18 px high.
    expect(placed).toEqual({ id: "o3", left: 82, top: 42 }); // 100 - 37 / 2, rounded
  });

  it("keeps the larger object's tag where two would overlap (the shelf, not its books)", () => {
    const placed = placeLabels([at("o1", 100, 60, 0.02), at("o2", 110, 65, 1.5)], 400, 300);
    expect(placed.map((p) => p.id)).toEqual(["o2"]);
  });

  it("draws apart tags side by side", () => {
    const placed = placeLabels([at("o1", 100, 60, 5), at("o2", 200, 60, 2)], 400, 300);
    expect(placed.map((p) => p.id).sort()).toEqual(["o1", "o2"]);
  });

  it("always draws the hovered or selected object's tag, first", () => {
    const placed = placeLabels([at("o1", 100, 60, 0.1, true), at("o2", 105, 60, 2)], 400, 300);
    expect(placed.map((p) => p.id)).toEqual(["o1"]);
    const offView = placeLabels([at("o7", -50, 60, 1, true)], 400, 300);
    expect(offView.map((p) => p.id)).toEqual(["o7"]);
  });

  it("leaves out tags that would leave the view", () => {
    expect(placeLabels([at("o1", 5, 60, 1), at("o2", 200, 10, 1)], 400, 300)).toEqual([]);
  });
});
