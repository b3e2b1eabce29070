// The TypeScript preprocessing and decoding of the object detector against the shared vectors
// (shared_schema/vectors/detector_model.json, written from runtime.py): the input tensor the
// same bit for bit (its float32 bytes' sha256), its samples and channel means within 1e-6, and
// the decoded boxes of the backend's raw rows the same classes in the same order, to 1e-4.
import { DETECTOR_MODEL } from "@holiscene/schema";
import { describe, expect, it } from "vitest";
import vectorsText from "../../../shared_schema/vectors/detector_model.json?raw";
import {
  boxIou,
  type DetectedBox,
  decodeDetections,
  detectorInput,
  INPUT_SIZE,
  isFlatPhoto,
  labelMapping,
  MIN_BOX_PX,
  NMS_IOU,
  SCORE_THRESHOLD,
} from "./detectorTensor";

interface EncodedPhoto {
  width: number;
  height: number;
  encoding: "zlib";
  rgb_base64: string;
}

interface ExpectedBox {
  bbox: number[];
  score: number;
  class: string;
  source_class: string;
}

interface Rows {
  shape: number[];
  data: number[];
}

interface PhotoCase {
  name: string;
  image: EncodedPhoto;
  expected: {
    images: {
      shape: number[];
      float32_sha256: string;
      channel_means: number[];
      samples: { index: number[]; data: number[] };
    };
    detections: Rows;
    boxes: ExpectedBox[];
    boxes_low_threshold: ExpectedBox[];
  };
}

interface DecodeCase {
  name: string;
  width: number;
  height: number;
  label_space: "coco80" | "nyu40";
  classes: string[] | null;
  score_threshold: number;
  detections: Rows;
  expected: ExpectedBox[];
}

const vectors = JSON.parse(vectorsText) as {
  model: { label_space: string; classes: string[] };
  contract: { input_size: number; score_threshold: number; nms_iou: number; min_box_px: number };
  low_threshold: number;
  tolerance: { inputs: number; detections: number; boxes: number };
  cases: PhotoCase[];
  /** Photos preprocessed only (a pixel, a column, a row): no model output. */
  preprocess_cases: {
    name: string;
    image: EncodedPhoto;
    expected: Pick<PhotoCase["expected"], "images">;
  }[];
  decode_cases: DecodeCase[];
};
const INPUT_TOLERANCE = 1e-6;
const BOX_TOLERANCE = 1e-4;
const COCO = labelMapping({ label_space: "coco80", classes: DETECTOR_MODEL.coco_classes });
/** The mapping of the model the vectors were made from (COCO, or a model of NYU-40 classes). */
const MODEL = labelMapping(vectors.model);

async function rgbBytes(photo: EncodedPhoto): Promise<Uint8Array> {
  const packed = Uint8Array.from(atob(photo.rgb_base64), (c) => c.charCodeAt(0));
  const stream = new Blob([packed]).stream().pipeThrough(new DecompressionStream("deflate"));
  const rgb = new Uint8Array(await new Response(stream).arrayBuffer());
  expect(rgb.length).toBe(photo.width * photo.height * 3);
  return rgb;
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

async function sha256(values: Float32Array<ArrayBuffer>): Promise<string> {
  const digest = await crypto.subtle.digest("SHA-256", values);
  return Array.from(new Uint8Array(digest), (b) => b.toString(16).padStart(2, "0")).join("");
}

async function expectTensor(
  tensor: Float32Array<ArrayBuffer>,
  expected: PhotoCase["expected"]["images"],
) {
  expect(tensor.length).toBe(expected.shape.reduce((a, b) => a * b, 1));
  const { index, data } = expected.samples;
  let worst = 0;
  index.forEach((at, i) => {
    worst = Math.max(worst, Math.abs((tensor[at] as number) - (data[i] as number)));
  });
  expect(worst).toBeLessThanOrEqual(INPUT_TOLERANCE);
  const sums = new Float64Array(3);
  for (let i = 0; i < tensor.length; i++)
    sums[i % 3] = (sums[i % 3] as number) + (tensor[i] as number);
  sums.forEach((sum, c) => {
    const mean = sum / (tensor.length / 3);
    expect(Math.abs(mean - (expected.channel_means[c] as number))).toBeLessThanOrEqual(
      INPUT_TOLERANCE,
    );
  });
  expect(await sha256(tensor)).toBe(expected.float32_sha256);
}

function expectBoxes(actual: DetectedBox[], expected: ExpectedBox[]) {
  expect(actual.map((b) => `${b.cls} ${b.sourceClass}`)).toEqual(
    expected.map((b) => `${b.class} ${b.source_class}`),
  );
  actual.forEach((box, i) => {
    const want = expected[i] as ExpectedBox;
    box.bbox.forEach((v, k) => {
      expect(Math.abs(v - (want.bbox[k] as number)), `box ${i}[${k}]`).toBeLessThanOrEqual(
        BOX_TOLERANCE,
      );
    });
    expect(Math.abs(box.score - want.score)).toBeLessThanOrEqual(BOX_TOLERANCE);
  });
}

describe("object detector preprocessing and decoding against the shared vectors", () => {
  it("uses the vectors' contract and tolerances", () => {
    expect(vectors.contract).toEqual({
      input_size: INPUT_SIZE,
      score_threshold: SCORE_THRESHOLD,
      nms_iou: NMS_IOU,
      min_box_px: MIN_BOX_PX,
    });
    expect(vectors.tolerance).toEqual({
      inputs: INPUT_TOLERANCE,
      detections: 1e-4,
      boxes: BOX_TOLERANCE,
    });
    expect(vectors.cases.length).toBeGreaterThanOrEqual(3);
  });

  for (const c of [...vectors.cases, ...vectors.preprocess_cases]) {
    const { width, height } = c.image;
    it(`${c.name}: RGBA and RGB pixels give Python's input tensor`, async () => {
      const rgb = await rgbBytes(c.image);
      await expectTensor(detectorInput({ width, height, data: rgba(rgb) }), c.expected.images);
      await expectTensor(detectorInput({ width, height, data: rgb }), c.expected.images);
    });
  }

  for (const c of vectors.cases) {
    const { width, height } = c.image;

    it(`${c.name}: the backend's raw rows decode to the same boxes`, () => {
      const raw = Float32Array.from(c.expected.detections.data);
      expectBoxes(decodeDetections(raw, width, height, MODEL), c.expected.boxes);
      expectBoxes(
        decodeDetections(raw, width, height, MODEL, vectors.low_threshold),
        c.expected.boxes_low_threshold,
      );
    });
  }

  for (const c of vectors.decode_cases) {
    it(`${c.name}: hand-made rows decode to the same boxes`, () => {
      const mapping =
        c.label_space === "nyu40"
          ? labelMapping({ label_space: "nyu40", classes: c.classes ?? [] })
          : COCO;
      const raw = Float32Array.from(c.detections.data);
      expectBoxes(decodeDetections(raw, c.width, c.height, mapping, c.score_threshold), c.expected);
    });
  }

  it("fails a tensor whose photo is off by one level in one pixel", async () => {
    const c = vectors.cases.find((k) => k.name === "odd-97x61") as PhotoCase;
    const rgb = await rgbBytes(c.image);
    rgb[3 * (30 * 97 + 48)] = ((rgb[3 * (30 * 97 + 48)] as number) + 1) % 256;
    const tensor = detectorInput({ width: 97, height: 61, data: rgb });
    expect(await sha256(tensor)).not.toBe(c.expected.images.float32_sha256);
  });
});

describe("detector helpers", () => {
  it("interpolates with half-pixel centres and clamps at the edges", () => {
    // 1 x 2 photo (black, white) stretched to 4 x 4: x = (c + 0.5) / 2 - 0.5 -> 0, 0.25, 0.75, 1.
    const photo = { width: 2, height: 1, data: [0, 0, 0, 255, 255, 255] };
    const tensor = detectorInput(photo, 4);
    expect(Array.from(tensor.slice(0, 12))).toEqual([
      0, 0, 0, 63.75, 63.75, 63.75, 191.25, 191.25, 191.25, 255, 255, 255,
    ]);
    expect(Array.from(tensor.slice(36, 48))).toEqual(Array.from(tensor.slice(0, 12)));
    expect(() => detectorInput({ width: 2, height: 2, data: [1, 2, 3] })).toThrow(/bytes per/);
  });

  it("measures IoU as the backend does", () => {
    expect(boxIou([0, 0, 10, 10], [5, 0, 15, 10])).toBeCloseTo(1 / 3, 12);
    expect(boxIou([0, 0, 10, 10], [20, 20, 30, 30])).toBe(0);
    expect(boxIou([0, 0, 0, 0], [0, 0, 0, 0])).toBe(0);
  });

  it("maps classes by the metadata's label space", () => {
    expect(COCO.toNyu40[DETECTOR_MODEL.coco_classes.indexOf("couch")]).toBe("sofa");
    expect(COCO.toNyu40[DETECTOR_MODEL.coco_classes.indexOf("dog")]).toBeNull();
    expect(labelMapping({ label_space: "nyu40", classes: ["chair", "lamp"] }).toNyu40).toEqual([
      "chair",
      "lamp",
    ]);
    expect(() => labelMapping({ label_space: "nyu40", classes: ["chair", "dog"] })).toThrow(
      /not in NYU-40: dog/,
    );
    expect(() => labelMapping({ label_space: "coco80", classes: ["chair"] })).toThrow(
      /does not match/,
    );
    expect(() => labelMapping({ label_space: "voc", classes: ["chair"] })).toThrow(/unknown/);
  });
});

describe("isFlatPhoto", () => {
  const photo = (values: number[], stride = 4) => ({
    width: values.length,
    height: 1,
    data: values.flatMap((v) => (stride === 4 ? [v, v, v, 255] : [v, v, v])),
  });

  it("finds a black or one-grey photo flat, with 3 or 4 bytes per pixel", () => {
    expect(isFlatPhoto(photo([0, 0, 0, 0]))).toBe(true);
    expect(isFlatPhoto(photo([128, 129, 128, 129], 3))).toBe(true);
  });

  it("finds a photo with detail not flat", () => {
    expect(isFlatPhoto(photo([0, 10, 0, 10]))).toBe(false);
  });
});
