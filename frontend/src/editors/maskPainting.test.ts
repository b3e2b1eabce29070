// Masks drawn by hand: brush strokes in and out, polygons, and the round trip through the
// contract's run-length Mask (checked against maskRaster's decoding, the overlay's reader).
import type { Mask } from "@holiscene/schema";
import { describe, expect, it } from "vitest";
import { decodeMask } from "../views/photo/maskRaster";
import { MaskRaster, type PixelRect } from "./maskPainting";

const PHOTO: PixelRect = { left: 0, top: 0, right: 40, bottom: 30 };

/** The set pixels as "x,y" strings, for comparing shapes. */
function pixels(raster: MaskRaster): Set<string> {
  const set = new Set<string>();
  for (let y = raster.window.top; y < raster.window.bottom; y++) {
    for (let x = raster.window.left; x < raster.window.right; x++) {
      if (raster.has(x, y)) set.add(`${x},${y}`);
    }
  }
  return set;
}

/** The photo pixels a stored mask covers. */
function maskPixels(mask: Mask): Set<string> {
  const bits = decodeMask(mask);
  const [width] = mask.size;
  const set = new Set<string>();
  bits.forEach((bit, i) => {
    if (bit) set.add(`${mask.origin[0] + (i % width)},${mask.origin[1] + Math.floor(i / width)}`);
  });
  return set;
}

describe("brush strokes", () => {
  it("paints a dot of the brush's radius around a point", () => {
    const raster = new MaskRaster(PHOTO);
    raster.paintStroke([[10, 10]], 3, 1);
    // Pixel centres within 3 of (10, 10): 8 in each quadrant (a disc of area ~28.3).
    expect(raster.count()).toBe(32);
    expect(raster.has(9, 9)).toBe(true);
    expect(raster.has(12, 8)).toBe(true);
    expect(raster.has(12, 7)).toBe(false);
    expect(raster.has(13, 10)).toBe(false);
    expect(raster.has(12, 12)).toBe(false);
  });

  it("paints a capsule along a polyline, and the eraser takes it out again", () => {
    const raster = new MaskRaster(PHOTO);
    const changed = raster.paintStroke(
      [
        [5, 5],
        [25, 5],
      ],
      2,
      1,
    );
    expect(changed).toEqual({ left: 3, top: 3, right: 27, bottom: 7 });
    for (let x = 5; x < 25; x++) {
      expect(raster.has(x, 4) && raster.has(x, 5) && raster.has(x, 3)).toBe(true);
      expect(raster.has(x, 7)).toBe(false);
    }
    const before = raster.count();
    raster.paintStroke([[15, 5]], 2, 0);
    expect(raster.has(15, 4)).toBe(false);
    expect(raster.has(20, 4)).toBe(true);
    expect(raster.count()).toBe(before - 12);
  });

  it("a thin brush still paints the pixel under the pointer", () => {
    const raster = new MaskRaster(PHOTO);
    raster.paintStroke([[7, 8]], 0.1, 1);
    expect(raster.count()).toBeGreaterThan(0);
    expect(raster.has(6, 7) || raster.has(7, 8)).toBe(true);
  });

  it("keeps strokes to its window", () => {
    const raster = new MaskRaster({ left: 10, top: 10, right: 20, bottom: 20 });
    const changed = raster.paintStroke([[10, 10]], 4, 1);
    expect(changed).toEqual({ left: 10, top: 10, right: 14, bottom: 14 });
    expect(raster.has(9, 10)).toBe(false);
    expect(raster.has(10, 10)).toBe(true);
  });

  it("an eraser stroke beside the mask leaves the same pixels", () => {
    const before = new MaskRaster({ left: 0, top: 0, right: 40, bottom: 40 });
    before.paintStroke([[10, 10]], 4, 1);
    const after = before.copy();
    after.paintStroke([[30, 30]], 4, 0); // nothing there to erase
    expect(after.samePixels(before)).toBe(true);
    after.paintStroke([[10, 10]], 2, 0);
    expect(after.samePixels(before)).toBe(false);
    expect(before.samePixels(new MaskRaster({ left: 0, top: 0, right: 40, bottom: 41 }))).toBe(
      false,
    );
  });
});

describe("polygons", () => {
  it("fills the pixels whose centres are inside", () => {
    const raster = new MaskRaster(PHOTO);
    raster.fillPolygon(
      [
        [2, 3],
        [12, 3],
        [12, 8],
        [2, 8],
      ],
      1,
    );
    expect(raster.count()).toBe(10 * 5);
    expect(raster.extent()).toEqual({ left: 2, top: 3, right: 12, bottom: 8 });
  });

  it("fills a triangle about half of its box, and subtracts with 0", () => {
    const raster = new MaskRaster(PHOTO);
    raster.fillPolygon(
      [
        [0, 0],
        [20, 0],
        [0, 20],
      ],
      1,
    );
    expect(raster.count()).toBeGreaterThan(180);
    expect(raster.count()).toBeLessThan(220);
    expect(raster.has(1, 1)).toBe(true);
    expect(raster.has(15, 15)).toBe(false);
    raster.fillPolygon(
      [
        [0, 0],
        [10, 0],
        [10, 10],
        [0, 10],
      ],
      0,
    );
    expect(raster.has(1, 1)).toBe(false);
    expect(raster.has(12, 2)).toBe(true);
  });

  it("ignores fewer than three points", () => {
    const raster = new MaskRaster(PHOTO);
    raster.fillPolygon(
      [
        [1, 1],
        [9, 9],
      ],
      1,
    );
    expect(raster.count()).toBe(0);
  });
});

describe("the contract's Mask", () => {
  it("encodes the set pixels in a window cropped to them, runs starting with 0", () => {
    const raster = new MaskRaster(PHOTO);
    raster.fillPolygon(
      [
        [4, 2],
        [7, 2],
        [7, 4],
        [4, 4],
      ],
      1,
    );
    raster.paintStroke([[9.5, 5.5]], 0.5, 1);
    const mask = raster.toMask();
    expect(mask).toEqual({
      origin: [4, 2],
      size: [6, 4],
      // Rows 2-3: three set then three clear; row 4 clear; row 5: only x = 9.
      rle: [0, 3, 3, 3, 3 + 6 + 5, 1],
      source: "manual",
    });
    expect(mask?.rle.reduce((a, b) => a + b, 0)).toBe(6 * 4);
  });

  it("starts with an empty run of 0 when the first pixel is set", () => {
    const raster = new MaskRaster(PHOTO);
    raster.paintStroke([[0.5, 0.5]], 0.5, 1);
    expect(raster.toMask()?.rle).toEqual([0, 1]);
  });

  it("has no mask when nothing is set", () => {
    expect(new MaskRaster(PHOTO).toMask()).toBeNull();
  });

  it("reads a stored mask and writes the same pixels back", () => {
    const raster = new MaskRaster(PHOTO);
    raster.paintStroke(
      [
        [8, 6],
        [30, 20],
        [12, 25],
      ],
      3.5,
      1,
    );
    raster.fillPolygon(
      [
        [14, 10],
        [20, 10],
        [17, 16],
      ],
      0,
    );
    const mask = raster.toMask("manual") as Mask;
    expect(maskPixels(mask)).toEqual(pixels(raster));
    const again = MaskRaster.fromMask(mask, PHOTO);
    expect(pixels(again)).toEqual(pixels(raster));
    expect(again.toMask()).toEqual(mask);
  });

  it("drops a stored mask's pixels outside the window", () => {
    const stored: Mask = { origin: [5, 5], size: [4, 2], rle: [0, 8], source: "grabcut" };
    const raster = MaskRaster.fromMask(stored, { left: 7, top: 0, right: 40, bottom: 6 });
    expect([...pixels(raster)].sort()).toEqual(["7,5", "8,5"]);
  });

  it("a copy is independent of the original", () => {
    const raster = new MaskRaster(PHOTO);
    raster.paintStroke([[5, 5]], 2, 1);
    const copy = raster.copy();
    copy.paintStroke([[5, 5]], 2, 0);
    expect(copy.count()).toBe(0);
    expect(raster.count()).toBeGreaterThan(0);
  });
});
