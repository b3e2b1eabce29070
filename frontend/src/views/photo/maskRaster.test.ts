// The hit map: which object's mask is under a photo point, smaller objects on top.
import type { Mask, SceneObject } from "@holiscene/schema";
import { describe, expect, it } from "vitest";
import { sceneObject } from "../../testing/sceneDocuments";
import { decodeMask, HitMap, maskPathData, objectRegion } from "./maskRaster";

/** A mask from rows of "." and "#" at `origin`. */
function mask(origin: [number, number], rows: string[]): Mask {
  const bits = rows.join("");
  const rle: number[] = [];
  let inside = false;
  let run = 0;
  for (const c of bits) {
    if ((c === "#") !== inside) {
      rle.push(run);
      run = 0;
      inside = !inside;
    }
    run += 1;
  }
  rle.push(run);
  return { origin, size: [rows[0]?.length ?? 0, rows.length], rle, source: "manual" };
}

function withMask(id: string, m: Mask): SceneObject {
  const [x, y] = m.origin;
  return { ...sceneObject(id, "box", [x, y, x + m.size[0], y + m.size[1]]), mask: m };
}

const at = (map: HitMap, points: [number, number][]) => points.map(([x, y]) => map.at(x, y));

describe("HitMap", () => {
  const big = withMask("big", mask([1, 1], ["####", "####", "####"]));
  const small = withMask("small", mask([2, 2], ["#.", "##"]));
  const cut = withMask("cut", mask([-1, 4], ["###", ".##"])); // its window leaves the photo

  const points: [number, number][] = [
    [1.5, 1.5],
    [2.5, 2.5],
    [3.2, 2.9],
    [3.5, 3.5],
    [4.9, 3.1],
    [0, 0],
    [0.5, 4.5],
    [0.5, 5.5],
    [1.5, 4.5],
    [5, 1],
  ];

  it("tells the smaller object where masks overlap, nothing outside the masks", () => {
    const placed = [big, small, cut].map((object) => ({ object, region: objectRegion(object) }));
    const map = new HitMap(6, 6, placed);
    expect(at(map, points)).toEqual([
      "big",
      "small",
      "big", // small's hole
      "small",
      "big",
      null,
      "cut",
      "cut",
      "cut",
      null,
    ]);
  });

  it("gives the same answers on a photo large enough to be sampled", () => {
    const scaled = (o: SceneObject): SceneObject => {
      const m = o.mask as Mask;
      const rows = Array.from({ length: m.size[1] * 200 }, () => "");
      const bits = objectRegion(o).bits as Uint8Array;
      for (let y = 0; y < rows.length; y++) {
        let row = "";
        for (let x = 0; x < m.size[0] * 200; x++)
          row += bits[Math.floor(y / 200) * m.size[0] + Math.floor(x / 200)] ? "#" : ".";
        rows[y] = row;
      }
      return withMask(o.id, mask([m.origin[0] * 200, m.origin[1] * 200], rows));
    };
    const objects = [big, small].map(scaled);
    const map = new HitMap(
      1200,
      1200,
      objects.map((object) => ({ object, region: objectRegion(object) })),
    );
    const inside = points.slice(0, 6).map(([x, y]) => [x * 200, y * 200] as [number, number]);
    expect(at(map, inside)).toEqual(["big", "small", "big", "small", "big", null]);
  });
});

describe("objectRegion", () => {
  /** Area and centroid counted pixel by pixel from the rows, the slow way. */
  function counted(origin: [number, number], rows: string[]) {
    let area = 0;
    let sumX = 0;
    let sumY = 0;
    rows.forEach((row, y) => {
      [...row].forEach((c, x) => {
        if (c !== "#") return;
        area += 1;
        sumX += x;
        sumY += y;
      });
    });
    return { area, centroid: [origin[0] + sumX / area + 0.5, origin[1] + sumY / area + 0.5] };
  }

  it("sums area and centroid over runs that wrap onto later rows", () => {
    const cases: [[number, number], string[]][] = [
      [
        [3, 7],
        ["..##", "####", "#..."],
      ], // one run across three rows
      [[0, 0], ["#"]],
      [
        [10, 2],
        [".#.#.", "#####", ".....", "##..#"],
      ],
      [
        [5, 5],
        ["######", "######"],
      ],
    ];
    for (const [origin, rows] of cases) {
      const region = objectRegion(withMask("m", mask(origin, rows)));
      const want = counted(origin, rows);
      expect(region.area).toBe(want.area);
      expect(region.centroid[0]).toBeCloseTo(want.centroid[0] ?? 0, 9);
      expect(region.centroid[1]).toBeCloseTo(want.centroid[1] ?? 0, 9);
      expect([...(region.bits ?? [])].join("")).toBe(
        rows.join("").replaceAll("#", "1").replaceAll(".", "0"),
      );
    }
  });
});

/** The pixels the path data's rectangles cover, in the mask's window, as decodeMask gives. */
function pathPixels(data: string, m: Mask): Uint8Array {
  const [width, height] = m.size;
  const bits = new Uint8Array(width * height);
  const pattern = /M(-?\d+) (-?\d+)h(\d+)v(\d+)h-(\d+)z/g;
  let consumed = 0;
  for (const found of data.matchAll(pattern)) {
    const [, x = 0, y = 0, w = 0, h = 0, back = -1] = found.map(Number);
    expect(back).toBe(w);
    consumed += String(found[0]).length;
    for (let row = y - m.origin[1]; row < y - m.origin[1] + h; row++)
      for (let column = x - m.origin[0]; column < x - m.origin[0] + w; column++) {
        expect(bits[row * width + column]).toBe(0); // no pixel covered twice
        bits[row * width + column] = 1;
      }
  }
  expect(consumed).toBe(data.length); // nothing but rectangles
  return bits;
}

describe("maskPathData", () => {
  it("covers exactly the mask's pixels, growing rectangles over repeated rows", () => {
    const shapes = [
      mask([3, 7], ["####", "####", "####"]),
      mask([0, 0], [".##.", "#..#", "#..#", "....", ".##."]),
      mask([5, 1], ["#", ".", "#"]),
      mask([2, 2], ["......"]),
    ];
    for (const m of shapes) expect(pathPixels(maskPathData(m), m)).toEqual(decodeMask(m));
    // A solid window is one rectangle; two identical rows of two runs are two.
    expect(maskPathData(shapes[0] as Mask)).toBe("M3 7h4v3h-4z");
    expect(maskPathData(mask([0, 0], ["#.#", "#.#"]))).toBe("M0 0h1v2h-1zM2 0h1v2h-1z");
  });

  it("matches random masks, runs wrapping across rows included", () => {
    let seed = 7;
    const random = () => {
      seed = (seed * 1103515245 + 12345) % 2147483648;
      return seed / 2147483648;
    };
    for (let n = 0; n < 50; n++) {
      const width = 1 + Math.floor(random() * 12);
      const height = 1 + Math.floor(random() * 9);
      const rows = Array.from({ length: height }, () =>
        Array.from({ length: width }, () => (random() < 0.5 ? "#" : ".")).join(""),
      );
      const m = mask([Math.floor(random() * 5), Math.floor(random() * 5)], rows);
      expect(pathPixels(maskPathData(m), m)).toEqual(decodeMask(m));
    }
  });
});
