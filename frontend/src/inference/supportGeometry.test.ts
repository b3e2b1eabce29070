// The same cases as the backend's tests/pipeline/test_support_geometry.py.
import type { Camera } from "@holiscene/schema";
import { describe, expect, it } from "vitest";
import { invert, matMul, worldFromCv } from "../geometry/camera";
import type { ObjectInput } from "./preprocess";
import {
  offTheFloor,
  ruleOutImpossible,
  ruleOutTheWall,
  seenAgainstTheFloor,
  tooLargeToStandThere,
} from "./supportGeometry";
import { STRUCTURAL_COLUMNS, SUPPORT_TYPE_ORDER } from "./supportModel";

const camera = (pitch: number | null): Camera =>
  ({
    K: [
      [500, 0, 320],
      [0, 500, 240],
      [0, 0, 1],
    ],
    K_source: "given",
    pitch_deg: pitch,
    roll_deg: pitch === null ? null : 0,
    height_m: null,
  }) as unknown as Camera;

describe("the floor's horizon", () => {
  it("leaves a bottom edge above it off the floor", () => {
    const high = [100, 40, 200, 120];
    const low = [100, 300, 200, 420];
    expect(offTheFloor(camera(0), [high, low], 480)).toEqual([true, false]);
  });

  it("moves with the pitch (positive: looking down)", () => {
    const boxes = [
      [100, 0, 200, 40],
      [300, 0, 400, 80],
    ];
    expect(offTheFloor(camera(20), boxes, 480)).toEqual([true, false]);
    expect(offTheFloor(camera(-20), [[100, 300, 200, 400]], 480)).toEqual([true]);
  });

  it("keeps the floor when a box just below may hide the real bottom edge", () => {
    const wardrobe = [100, 20, 200, 200];
    expect(offTheFloor(camera(0), [wardrobe, [80, 205, 260, 400]], 480)).toEqual([false, false]);
    expect(offTheFloor(camera(0), [wardrobe, [400, 205, 500, 400]], 480)).toEqual([true, false]);
  });

  it("rules nothing out without pitch and roll", () => {
    expect(offTheFloor(camera(null), [[100, 40, 200, 120]], 480)).toEqual([false]);
    expect(offTheFloor(null, [[100, 40, 200, 120]], 480)).toEqual([false]);
  });
});

describe("ruling out impossible supporters", () => {
  const types = SUPPORT_TYPE_ORDER.length;
  const columns = 2 + STRUCTURAL_COLUMNS.length;
  const at = (row: number, column: number, type: string) =>
    row * columns * types + column * types + SUPPORT_TYPE_ORDER.indexOf(type as never);
  const floor = 2 + STRUCTURAL_COLUMNS.indexOf("floor");
  const wall = 2 + STRUCTURAL_COLUMNS.indexOf("wall");

  it("takes the floor and the objects beside it away, and the rest sums to 1", () => {
    const picture = [0, 0, 100, 150];
    const nightStand = [500, 300, 600, 420]; // far to the right: cannot hold the picture
    const table = new Float64Array(2 * columns * types);
    table[at(0, floor, "below")] = 0.5;
    table[at(0, 1, "below")] = 0.3;
    table[at(0, wall, "behind")] = 0.1;
    table[at(0, wall, "below")] = 0.1;
    table[at(1, floor, "below")] = 1;
    ruleOutImpossible(table, [picture, nightStand], [true, false]);
    expect(table[at(0, floor, "below")]).toBe(0);
    expect(table[at(0, 1, "below")]).toBe(0);
    expect(table[at(0, wall, "behind")]).toBeCloseTo(0.5);
    expect(table[at(1, floor, "below")]).toBe(1); // the other row is left as it was
  });

  it("keeps the row when nothing else would be left", () => {
    const table = new Float64Array(2 * columns * types);
    table[at(0, floor, "below")] = 1;
    ruleOutImpossible(
      table,
      [
        [0, 0, 100, 150],
        [500, 300, 600, 420],
      ],
      [true, false],
    );
    expect(table[at(0, floor, "below")]).toBe(1);
  });
});

describe("seen against the floor", () => {
  // Camera 1.4 m above the floor of a room 6 m deep ahead (x) and 5 m wide (z); pitched down
  // 20 degrees, the far wall's foot is at y = 179.8 in the middle of the photo.
  const room = [-1.4, 1.2].flatMap((y) => [
    [-1, y, -2.5],
    [6, y, -2.5],
    [6, y, 2.5],
    [-1, y, 2.5],
  ]);
  const picture = [300, 40, 340, 179.8 - 60]; // against the far wall
  const door = [300, 30, 340, 179.8 + 4]; // its foot on the wall's foot, about
  const books = [300, 380, 340, 420]; // on a table near the camera: floor behind them

  it("hangs on no wall what the floor is seen behind", () => {
    expect(seenAgainstTheFloor(camera(20), room, [picture, door, books])).toEqual([
      false,
      false,
      true,
    ]);
  });

  it("says nothing without a room or a camera pose", () => {
    expect(seenAgainstTheFloor(camera(null), room, [books])).toEqual([false]);
    expect(seenAgainstTheFloor(camera(20), null, [books])).toEqual([false]);
  });

  it("takes the wall from behind away, and the rest sums to 1", () => {
    const types = SUPPORT_TYPE_ORDER.length;
    const columns = 1 + STRUCTURAL_COLUMNS.length;
    const wallBehind =
      (1 + STRUCTURAL_COLUMNS.indexOf("wall")) * types + SUPPORT_TYPE_ORDER.indexOf("behind");
    const floorBelow =
      (1 + STRUCTURAL_COLUMNS.indexOf("floor")) * types + SUPPORT_TYPE_ORDER.indexOf("below");
    const table = new Float64Array(columns * types);
    table[wallBehind] = 0.9;
    table[floorBelow] = 0.1;
    ruleOutTheWall(table, 1, [true]);
    expect(table[wallBehind]).toBe(0);
    expect(table[floorBelow]).toBeCloseTo(1);
  });
});

describe("too large to stand there (the backend's test_metric_scale and test_support_geometry)", () => {
  const down = camera(20); // horizon at y = 58
  const worldFromPixel = matMul(worldFromCv(20, 0), invert(down.K));
  const highShelf = [400, 0, 560, 110]; // would span 3 m of floor 10 camera heights away

  it("judges what the photo shows of an object against its class's largest size", () => {
    expect(tooLargeToStandThere(worldFromPixel, "shelves", highShelf)).toBe(true);
    expect(tooLargeToStandThere(worldFromPixel, "shelves", [400, 0, 560, 150])).toBe(false);
    expect(tooLargeToStandThere(worldFromPixel, "bookshelf", [300, 60, 440, 256])).toBe(false);
    expect(tooLargeToStandThere(worldFromPixel, "otherprop", highShelf)).toBe(false);
    expect(tooLargeToStandThere(worldFromPixel, "shelves", [400, 0, 560, 40])).toBe(false);
  });

  const input = (cls: string, bbox: number[]): ObjectInput => ({
    cls,
    bbox: bbox as unknown as ObjectInput["bbox"],
    mask: null, // the box stands for the mask
  });

  it("takes the floor away unless other objects' pixels just below may hide its bottom", () => {
    const bed = [0, 100, 420, 480]; // its box reaches above the shelf's bottom at one side
    const objects = [input("shelves", highShelf), input("bed", bed)];
    expect(offTheFloor(down, [highShelf, bed], 480)).toEqual([false, false]);
    expect(offTheFloor(down, [highShelf, bed], 480, objects, 640)).toEqual([true, false]);
    const dresser = [380, 115, 600, 300]; // right below it, across its width
    const withDresser = [...objects, input("dresser", dresser)];
    expect(offTheFloor(down, [highShelf, bed, dresser], 480, withDresser, 640)[0]).toBe(false);
  });

  it("never judges an object the photo's bottom edge cuts", () => {
    const cut = [100, 200, 600, 479];
    expect(offTheFloor(down, [cut], 480, [input("night_stand", cut)], 640)).toEqual([false]);
  });
});
