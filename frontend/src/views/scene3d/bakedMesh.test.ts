// Baking meshes for the 3D view: world-space triangles lit once, recolourable per part, and
// closed solids told apart (drawn one-sided) from open or inconsistent meshes.
import * as THREE from "three";
import { describe, expect, it } from "vitest";
import { BakedGeometry, lambertShade, solidWinding } from "./bakedMesh";

const IDENTITY = new THREE.Matrix4();
const RED = new THREE.Color(1, 0, 0);
const GREEN = new THREE.Color(0, 1, 0);

function box(): THREE.BufferGeometry {
  return new THREE.BoxGeometry(1, 2, 3);
}

/** A box without normals, indexed over shared corners, as the pipeline's GLB stores one. */
function sharedCornerBox(): THREE.BufferGeometry {
  const geometry = new THREE.BufferGeometry();
  const corners = [];
  for (const x of [0, 1]) for (const y of [0, 1]) for (const z of [0, 1]) corners.push(x, y, z);
  geometry.setAttribute("position", new THREE.Float32BufferAttribute(corners, 3));
  // Corner i = 4x + 2y + z; each face's two triangles counter-clockwise seen from outside.
  const faces = [
    [0, 1, 3, 2], // x = 0
    [4, 6, 7, 5], // x = 1
    [0, 4, 5, 1], // y = 0
    [2, 3, 7, 6], // y = 1
    [0, 2, 6, 4], // z = 0
    [1, 5, 7, 3], // z = 1
  ];
  geometry.setIndex(faces.flatMap(([a, b, c, d]) => [a, b, c, a, c, d] as number[]));
  return geometry;
}

describe("solidWinding", () => {
  it("finds closed solids and which way they wind", () => {
    expect(solidWinding(box(), IDENTITY)).toBe(1); // split vertices: closed by position
    expect(solidWinding(sharedCornerBox(), IDENTITY)).toBe(1);
    const inverted = sharedCornerBox();
    const index = inverted.index?.array as Uint16Array;
    for (let k = 0; k < index.length; k += 3)
      [index[k + 1], index[k + 2]] = [index[k + 2] as number, index[k + 1] as number];
    expect(solidWinding(inverted, IDENTITY)).toBe(-1);
    expect(solidWinding(new THREE.SphereGeometry(1, 8, 6), IDENTITY)).toBe(1);
  });

  it("turns over with a mirroring placement", () => {
    expect(solidWinding(box(), new THREE.Matrix4().makeScale(-1, 1, 1))).toBe(-1);
    expect(solidWinding(box(), new THREE.Matrix4().makeScale(2, 3, 0.5))).toBe(1);
  });

  it("refuses open or inconsistently wound meshes", () => {
    expect(solidWinding(new THREE.PlaneGeometry(1, 1), IDENTITY)).toBe(0);
    expect(solidWinding(new THREE.CylinderGeometry(1, 1, 1, 8, 1, true), IDENTITY)).toBe(0);
    const mixed = sharedCornerBox();
    const index = mixed.index?.array as Uint16Array;
    [index[1], index[2]] = [index[2] as number, index[1] as number]; // one triangle flipped
    expect(solidWinding(mixed, IDENTITY)).toBe(0);
  });
});

describe("BakedGeometry", () => {
  it("moves parts into place and keeps their triangles", () => {
    const baked = new BakedGeometry([
      { geometry: box(), matrix: IDENTITY, colour: RED },
      { geometry: box(), matrix: new THREE.Matrix4().makeTranslation(10, 0, 0), colour: GREEN },
    ]);
    const { geometry } = baked;
    expect(geometry.index?.count).toBe(2 * 36);
    const bounds = new THREE.Box3().setFromBufferAttribute(
      geometry.getAttribute("position") as THREE.BufferAttribute,
    );
    expect(bounds.min.toArray()).toEqual([-0.5, -1, -1.5]);
    expect(bounds.max.toArray()).toEqual([10.5, 1, 1.5]);
  });

  it("lights each vertex as three.js's Lambert material would, and recolours one part", () => {
    const baked = new BakedGeometry([
      { geometry: sharedCornerBox(), matrix: IDENTITY, colour: RED },
      { geometry: sharedCornerBox(), matrix: IDENTITY, colour: GREEN },
    ]);
    const colours = baked.geometry.getAttribute("color");
    // Without normals each triangle is flat: 36 vertices per box, the first on the x = 0 face.
    expect(colours.count).toBe(72);
    const shade = lambertShade(new THREE.Vector3(-1, 0, 0));
    expect(colours.getX(0)).toBeCloseTo(shade.r, 6);
    expect(colours.getY(0)).toBe(0);
    const glow = new THREE.Color(0.1, 0.1, 0.1);
    baked.setColour(1, GREEN, glow);
    expect(baked.colourOf(1).g).toBeCloseTo(shade.g + 0.1, 6);
    expect(baked.colourOf(1).r).toBeCloseTo(0.1, 6);
    expect(baked.colourOf(0).r).toBeCloseTo(shade.r, 6); // the other part is untouched
  });

  it("faces the sun brighter than the ground", () => {
    const up = lambertShade(new THREE.Vector3(0, 1, 0));
    const down = lambertShade(new THREE.Vector3(0, -1, 0));
    expect(up.r).toBeGreaterThan(down.r);
  });

  it("turns a flipped part's triangles and normals the other way", () => {
    const [plain, flipped] = [false, true].map(
      (flip) =>
        new BakedGeometry([{ geometry: sharedCornerBox(), matrix: IDENTITY, colour: RED, flip }]),
    );
    const first = (baked: BakedGeometry | undefined) => baked?.colourOf(0).r ?? Number.NaN;
    // The first triangle lies on the x = 0 face: lit as facing -x, then as facing +x.
    expect(first(plain)).toBeCloseTo(lambertShade(new THREE.Vector3(-1, 0, 0)).r, 6);
    expect(first(flipped)).toBeCloseTo(lambertShade(new THREE.Vector3(1, 0, 0)).r, 6);
  });
});
