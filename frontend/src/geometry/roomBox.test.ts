// The room's edges on the photo: whole edges in front of the camera, cut ones crossing it.
import { describe, expect, it } from "vitest";
import { boxCorners } from "./boxes";
import { projectPoints, type Vec3 } from "./camera";
import { BOX_EDGES, projectBoxEdges } from "./roomBox";

const K: [Vec3, Vec3, Vec3] = [
  [500, 0, 320],
  [0, 500, 240],
  [0, 0, 1],
];

describe("projectBoxEdges", () => {
  it("projects the 12 edges of a box in front of the camera end to end", () => {
    const corners = boxCorners([5, 0, 0], [2, 2.5, 3], 15);
    const pixels = projectPoints(K, 8, -2, corners);
    const edges = projectBoxEdges(K, 8, -2, corners);
    expect(edges.length).toBe(12);
    edges.forEach(([a, b], e) => {
      const [i, j] = BOX_EDGES[e] as [number, number];
      expect(a[0]).toBeCloseTo(pixels[i]?.[0] ?? Number.NaN, 9);
      expect(b[1]).toBeCloseTo(pixels[j]?.[1] ?? Number.NaN, 9);
    });
  });

  it("cuts edges where they pass behind the camera and drops those wholly behind", () => {
    // The camera inside the room: the wall behind it is out of sight.
    const corners = boxCorners([1, 0, 0], [6, 2.5, 4], 0);
    const edges = projectBoxEdges(K, 0, 0, corners);
    // The back wall's 4 edges are behind; the 4 edges along x run from behind to the front.
    expect(edges.length).toBe(8);
    for (const [a, b] of edges) {
      for (const p of [a, b]) expect(p.every(Number.isFinite)).toBe(true);
    }
    // A cut edge along the floor heads into the image from far below it.
    const floorLeft = edges.find(([a, b]) => Math.max(a[1], b[1]) > 2000);
    expect(floorLeft).toBeDefined();
  });
});
