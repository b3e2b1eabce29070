// The 3D view's caption: the object and its box's size in metres.
import { describe, expect, it } from "vitest";
import { objectCaption } from "./objectCaption";

describe("objectCaption", () => {
  it("names the object and gives its 3D box's size and confidence", () => {
    const box = {
      center: [0, 0.5, 3] as [number, number, number],
      size: [0.5, 0.234, 0.21] as [number, number, number],
      yaw_deg: 0,
    };
    expect(
      objectCaption({ id: "o3", class: "night_stand", box_3d: box, box_3d_confidence: 0.876 }),
    ).toBe(
      "o3 night stand · 3D box 0.50 × 0.23 × 0.21 m (depth × height × width) · 87% likely right (box refiner)",
    );
    expect(objectCaption({ id: "d2", class: "lamp", box_3d: null, box_3d_confidence: null })).toBe(
      "d2 lamp · no 3D box",
    );
    // The detector's own name too, as the object list writes it.
    const clock = { id: "o15", class: "otherprop" as const, source_class: "clock" };
    expect(objectCaption({ ...clock, box_3d: null, box_3d_confidence: null })).toMatch(
      /^o15 otherprop \(clock\)/,
    );
  });
});
