// The object list's 3D box badge: shown only for a judged box, doubtful below one half.
import { describe, expect, it } from "vitest";
import { boxConfidence } from "./boxConfidence";

const box = {
  center: [0, 0, 3] as [number, number, number],
  size: [1, 1, 1] as [number, number, number],
  yaw_deg: 0,
};

describe("3D box confidence", () => {
  it("rounds the chance and marks doubtful boxes", () => {
    expect(boxConfidence({ box_3d: box, box_3d_confidence: 0.624 })).toMatchObject({
      text: "3D 62%",
      doubtful: false,
    });
    const doubtful = boxConfidence({ box_3d: box, box_3d_confidence: 0.21 });
    expect(doubtful).toMatchObject({ text: "3D 21%", doubtful: true });
    expect(doubtful?.title).toContain("check it in the 3D view");
  });

  it("shows nothing without a box or without a judgement", () => {
    expect(boxConfidence({ box_3d: null, box_3d_confidence: 0.9 })).toBeNull();
    expect(boxConfidence({ box_3d: box, box_3d_confidence: null })).toBeNull();
  });
});
