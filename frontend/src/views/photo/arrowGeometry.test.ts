// Where an arrow from an object supporter starts: under its child on the supporter, not at the
// supporter's centre (a shelf's arrows would fan out of one point).
import { describe, expect, it } from "vitest";
import { arrowFoot, type SupporterShape } from "./arrowGeometry";

/** A shelf from x 10-49, y 10-89 whose mask has boards (rows) at y 40 and y 80. */
function shelf(): SupporterShape {
  const width = 40;
  const height = 80;
  const bits = new Uint8Array(width * height);
  for (const y of [40, 80]) bits.fill(1, (y - 10) * width, (y - 9) * width);
  return {
    bbox: [10, 10, 50, 90],
    mask: { origin: [10, 10], size: [width, height], bits },
    centroid: [30, 60],
  };
}

describe("arrowFoot", () => {
  it("starts a supported-from-below arrow on the board under each child", () => {
    const books = arrowFoot("below", [14, 25, 22, 40], [18, 32], shelf(), 4);
    const vase = arrowFoot("below", [36, 62, 44, 80], [40, 71], shelf(), 4);
    expect(books).toEqual([18, 40.5]);
    expect(vase).toEqual([40, 80.5]);
  });

  it("keeps the start under the supporter's box for a child beside it", () => {
    const [x] = arrowFoot("below", [60, 20, 70, 40], [65, 30], shelf(), 4);
    expect(x).toBe(49.5);
  });

  it("keeps its length: a start on the child's centre moves straight down", () => {
    expect(arrowFoot("below", [26, 30, 34, 40.5], [30, 40.5], shelf(), 6)).toEqual([30, 46.5]);
    expect(arrowFoot("below", [26, 30, 34, 39], [30, 38.5], shelf(), 6)).toEqual([30, 44.5]);
  });

  it("uses the centre from behind, or where no supporter pixel is under the child", () => {
    expect(arrowFoot("behind", [14, 25, 22, 40], [18, 32], shelf(), 4)).toEqual([30, 60]);
    const empty = {
      ...shelf(),
      mask: { origin: [10, 10] as const, size: [40, 80] as const, bits: new Uint8Array(3200) },
    };
    expect(arrowFoot("below", [14, 25, 22, 40], [18, 32], empty, 4)).toEqual([30, 60]);
  });

  it("never starts a from-below arrow above its child's centre", () => {
    // Nothing of the shelf below this child at all: the supporter's centre it is.
    expect(arrowFoot("below", [14, 82, 22, 86], [18, 84], shelf(), 4)).toEqual([30, 60]);
  });

  it("takes the supporter's pixel nearest under the child where its own column shows none", () => {
    // A shelf whose bottom board shows only from x 10 to 19, under a child at x 30.
    const board = shelf();
    board.mask?.bits.fill(0);
    board.mask?.bits.fill(1, 70 * 40, 70 * 40 + 10);
    expect(arrowFoot("below", [26, 62, 34, 79], [30, 71], board, 4)).toEqual([19.5, 80.5]);
  });

  it("uses the box's top or bottom edge without a mask", () => {
    const box = { ...shelf(), mask: null };
    expect(arrowFoot("below", [14, 0, 22, 5], [18, 2], box, 4)).toEqual([18, 10]);
  });
});
