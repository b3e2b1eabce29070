// The Refine tool's box: the object's box grown by foreground strokes, kept in the photo.
import type { Stroke } from "@holiscene/schema";
import { describe, expect, it } from "vitest";
import { intoPhoto, refineBox } from "./refineBox";

const PHOTO = { left: 0, top: 0, right: 640, bottom: 480 };

describe("refine box", () => {
  it("is the object's box when the strokes lie inside it", () => {
    const stroke: Stroke = { points: [[120, 130]], radius: 5 };
    expect(refineBox([100, 100, 200, 200], [stroke], PHOTO)).toEqual([100, 100, 200, 200]);
  });

  it("grows to take in a foreground stroke painted past the box, brush and all", () => {
    const stroke: Stroke = {
      points: [
        [150, 150],
        [260, 90],
      ],
      radius: 8,
    };
    expect(refineBox([100, 100, 200, 200], [stroke], PHOTO)).toEqual([100, 82, 268, 200]);
  });

  it("stays inside the photo", () => {
    const stroke: Stroke = { points: [[635, 5]], radius: 20 };
    expect(refineBox([600, 10, 630, 40], [stroke], PHOTO)).toEqual([600, 0, 640, 40]);
  });

  it("moves points off the photo onto its edge", () => {
    expect(intoPhoto([-4, 500], PHOTO)).toEqual([0, 480]);
    expect(intoPhoto([12.5, 40], PHOTO)).toEqual([12.5, 40]);
  });
});
