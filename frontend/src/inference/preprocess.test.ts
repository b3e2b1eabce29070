// The TypeScript preprocessing against the shared vectors
// (shared_schema/vectors/relation_model.json, written from preprocess.py): every input tensor
// within 1e-6 of Python's, classes exactly, and the same objects kept.
import type { SceneObject } from "@holiscene/schema";
import { describe, expect, it } from "vitest";
import vectorsText from "../../../shared_schema/vectors/relation_model.json?raw";
import {
  areaResize,
  cellBounds,
  modelObjects,
  type RelationInputs,
  sceneInputs,
} from "./preprocess";

interface Tensor {
  shape: number[];
  data: number[];
}

interface VectorCase {
  name: string;
  image: { width: number; height: number; rgb_base64: string };
  objects: SceneObject[];
  model_objects: string[];
  expected: Record<"image" | "masks" | "boxes" | "classes" | "support_logits", Tensor>;
}

const vectors = JSON.parse(vectorsText) as {
  tolerance: { inputs: number };
  cases: VectorCase[];
};
const TOLERANCE = 1e-6;

function rgbBytes(base64: string): Uint8Array {
  return Uint8Array.from(atob(base64), (c) => c.charCodeAt(0));
}

/** The photo as a canvas gives it: RGBA. */
function rgba(rgb: Uint8Array): Uint8ClampedArray {
  const out = new Uint8ClampedArray((rgb.length / 3) * 4);
  for (let i = 0; i < rgb.length / 3; i++) {
    out.set(rgb.subarray(3 * i, 3 * i + 3), 4 * i);
    out[4 * i + 3] = 255;
  }
  return out;
}

/** Largest |actual - expected| and where. */
function maxDifference(actual: ArrayLike<number>, expected: readonly number[]) {
  expect(actual.length).toBe(expected.length);
  let worst = { at: -1, difference: 0 };
  for (let i = 0; i < expected.length; i++) {
    const difference = Math.abs((actual[i] as number) - (expected[i] as number));
    if (!(difference <= worst.difference)) worst = { at: i, difference };
  }
  return worst;
}

function expectInputs(inputs: RelationInputs, expected: VectorCase["expected"]) {
  expect(inputs.count).toBe(expected.classes.shape[0]);
  expect(Array.from(inputs.classes, Number)).toEqual(expected.classes.data);
  for (const name of ["image", "masks", "boxes"] as const) {
    const { difference, at } = maxDifference(inputs[name], expected[name].data);
    expect(difference, `${name}[${at}]`).toBeLessThanOrEqual(TOLERANCE);
  }
}

describe("relation model preprocessing against the shared vectors", () => {
  it("uses the vectors' tolerance", () => {
    expect(vectors.tolerance.inputs).toBe(TOLERANCE);
    expect(vectors.cases.map((c) => c.model_objects.length).sort((a, b) => a - b)).toEqual([
      1, 3, 20,
    ]);
  });

  for (const c of vectors.cases) {
    const { width, height, rgb_base64 } = c.image;
    const rgb = rgbBytes(rgb_base64);

    it(`${c.name}: keeps the same objects`, () => {
      expect(modelObjects(c.objects).map((o) => o.id)).toEqual(c.model_objects);
    });

    it(`${c.name}: RGBA pixels give Python's tensors`, () => {
      expectInputs(sceneInputs({ width, height, data: rgba(rgb) }, c.objects), c.expected);
    });

    it(`${c.name}: RGB pixels give the same`, () => {
      expectInputs(sceneInputs({ width, height, data: rgb }, c.objects), c.expected);
    });
  }

  it("fails a tensor that is off by more than the tolerance", () => {
    const c = vectors.cases[0] as VectorCase;
    const { width, height, rgb_base64 } = c.image;
    const rgb = rgbBytes(rgb_base64);
    rgb[0] = ((rgb[0] as number) + 1) % 256; // one channel of one pixel, by one level
    const inputs = sceneInputs({ width, height, data: rgb }, c.objects);
    expect(maxDifference(inputs.image, c.expected.image.data).difference).toBeGreaterThan(
      TOLERANCE,
    );
  });
});

describe("area resize", () => {
  it("has the contract's cell bounds, never empty", () => {
    const down = cellBounds(5, 2);
    expect([...down.starts, ...down.ends]).toEqual([0, 2, 2, 5]);
    const up = cellBounds(2, 5); // each cell one input row, rows repeated
    expect([...up.starts]).toEqual([0, 0, 0, 1, 1]);
    expect([...up.ends]).toEqual([1, 1, 1, 2, 2]);
  });

  it("averages over each cell in float64 and rounds once to float32", () => {
    // 3 x 4 of one channel to 2 x 2: rows {0}, {1, 2}; columns {0, 1}, {2, 3}.
    const values = [1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12];
    expect([...areaResize(values, 3, 4, 1, 2)]).toEqual([1.5, 3.5, 7.5, 9.5]);
    const third = areaResize([0, 0, 1], 1, 3, 1, 1)[0];
    expect(third).toBe(Math.fround(1 / 3));
  });
});
