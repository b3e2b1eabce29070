// The box tool's geometry: which handle a press grips, and boxes moved or resized by a drag
// staying inside the photo, the right way round and never thinner than MIN_BOX_PX.
import { describe, expect, it } from "vitest";
import {
  boxFromCorners,
  dragBox,
  gripAt,
  handlePoint,
  isBigEnough,
  MIN_BOX_PX,
} from "./boxGeometry";

const BOX = [100, 50, 200, 150];

describe("box handles", () => {
  it("sit on the corners and the middles of the sides", () => {
    expect(handlePoint(BOX, "nw")).toEqual([100, 50]);
    expect(handlePoint(BOX, "e")).toEqual([200, 100]);
    expect(handlePoint(BOX, "s")).toEqual([150, 150]);
  });

  it("a press grips the nearest handle within reach, else the inside, else nothing", () => {
    expect(gripAt(BOX, [203, 48], 6)).toBe("ne");
    expect(gripAt(BOX, [150, 152], 6)).toBe("s");
    expect(gripAt(BOX, [140, 90], 6)).toBe("move");
    expect(gripAt(BOX, [90, 90], 6)).toBeNull();
    // A tiny box: the handle nearest the press wins, not the first in the list.
    expect(gripAt([10, 10, 14, 14], [14, 14], 6)).toBe("se");
  });
});

describe("dragging a box", () => {
  it("moves it whole, stopped at the photo's edge", () => {
    expect(dragBox(BOX, "move", 10, -5, 640, 480)).toEqual([110, 45, 210, 145]);
    expect(dragBox(BOX, "move", -500, 900, 640, 480)).toEqual([0, 380, 100, 480]);
  });

  it("resizes the gripped sides only, clamped to the photo", () => {
    expect(dragBox(BOX, "e", 30, 99, 640, 480)).toEqual([100, 50, 230, 150]);
    expect(dragBox(BOX, "nw", -200, -200, 640, 480)).toEqual([0, 0, 200, 150]);
  });

  it("flips past the opposite side and keeps a minimum size", () => {
    expect(dragBox(BOX, "w", 150, 0, 640, 480)).toEqual([200, 50, 250, 150]);
    const thin = dragBox(BOX, "e", -100, 0, 640, 480);
    expect(thin[2] - thin[0]).toBe(MIN_BOX_PX);
    expect(thin[0]).toBe(100);
  });

  it("a drawn box is spanned by its corners inside the photo; a click is too small", () => {
    expect(boxFromCorners([300, 20], [-10, 600], 640, 480)).toEqual([0, 20, 300, 480]);
    expect(isBigEnough(boxFromCorners([5, 5], [7, 30], 640, 480))).toBe(false);
    expect(isBigEnough(boxFromCorners([5, 5], [9, 30], 640, 480))).toBe(true);
  });
});
