// The object detector's input tensor and the decoding of its rows: the TypeScript twin of
// backend/src/holiscene/learning/detector/runtime.py (`bilinear_resize`, `preprocess`,
// `decode`). The contract is shared_schema/holiscene_schema/detector_model.py (DETECTOR_MODEL
// here); the shared vectors (shared_schema/vectors/detector_model.json) hold both sides to the
// same numbers. Every step does the same float64 operations in the same order as numpy, so the
// input tensor agrees bit for bit and the boxes to the last digit.
import { DETECTOR_MODEL, NYU40_CLASSES } from "@holiscene/schema";
import type { PixelImage } from "./preprocess";

export const INPUT_SIZE: number = DETECTOR_MODEL.input_size;
export const SCORE_THRESHOLD: number = DETECTOR_MODEL.score_threshold;
export const NMS_IOU: number = DETECTOR_MODEL.nms_iou;
export const MIN_BOX_PX: number = DETECTOR_MODEL.min_box_px;
export const FLAT_PHOTO_STD: number = DETECTOR_MODEL.flat_photo_std;

/** A photo of one flat colour (3 or 4 bytes per pixel): its grey levels, each pixel's mean of
 * R, G and B, vary by less than FLAT_PHOTO_STD. The detector is not run on it (the backend's
 * objects_from_detector stage skips it too): it still "sees" objects in a blank frame. */
export function isFlatPhoto(photo: PixelImage): boolean {
  const count = photo.width * photo.height;
  if (count === 0) return true;
  const stride = photo.data.length / count;
  let sum = 0;
  let sumSquares = 0;
  for (let i = 0; i < count; i++) {
    const at = stride * i;
    const grey =
      ((photo.data[at] ?? 0) + (photo.data[at + 1] ?? 0) + (photo.data[at + 2] ?? 0)) / 3;
    sum += grey;
    sumSquares += grey * grey;
  }
  const mean = sum / count;
  return Math.sqrt(Math.max(0, sumSquares / count - mean * mean)) < FLAT_PHOTO_STD;
}
const ROW = DETECTOR_MODEL.output.shape[2]; // x1, y1, x2, y2, score, class index

export type Box = [number, number, number, number];

/** One decoded detection in photo pixels, its class mapped to NYU-40. */
export interface DetectedBox {
  bbox: Box;
  score: number;
  /** The NYU-40 class. */
  cls: string;
  /** The model's own class name. */
  sourceClass: string;
}

/** A model's classes and what each becomes in NYU-40 (null: dropped). */
export interface LabelMapping {
  classes: readonly string[];
  toNyu40: readonly (string | null)[];
}

/** Where each output row or column samples the photo: runtime.py's `ys` / `xs`. */
function samplePoints(length: number, size: number) {
  const low = new Int32Array(size);
  const high = new Int32Array(size);
  const weight = new Float64Array(size);
  for (let i = 0; i < size; i++) {
    // (i + 0.5) * length / size - 0.5, clamped to [0, length - 1], as numpy evaluates it.
    const at = Math.min(Math.max(((i + 0.5) * length) / size - 0.5, 0), length - 1);
    const floor = Math.floor(at);
    low[i] = floor;
    high[i] = Math.min(floor + 1, length - 1);
    weight[i] = at - floor;
  }
  return { low, high, weight };
}

/**
 * The model's `images` input [1, S, S, 3] (flat, row by row, RGB fastest): the photo's values
 * (0-255) stretched to S x S by bilinear resampling with half-pixel centres, clamped at the
 * edges, in float64 and rounded once to float32. `image.data` holds 3 (RGB) or 4 (RGBA, e.g.
 * a canvas's ImageData) bytes per pixel.
 */
export function detectorInput(
  image: PixelImage,
  size: number = INPUT_SIZE,
): Float32Array<ArrayBuffer> {
  const { width, height, data } = image;
  if (!(width >= 1 && height >= 1)) throw new Error(`expected a photo, got ${width}x${height}`);
  const stride = data.length / (width * height);
  if (stride !== 3 && stride !== 4) {
    throw new Error(`expected 3 or 4 bytes per pixel for ${width}x${height}, got ${data.length}`);
  }
  const rows = samplePoints(height, size);
  const columns = samplePoints(width, size);
  const left = Int32Array.from(columns.low, (x) => x * stride);
  const right = Int32Array.from(columns.high, (x) => x * stride);
  const out = new Float32Array(size * size * 3);
  const rowBytes = width * stride;
  let k = 0;
  for (let r = 0; r < size; r++) {
    const upper = (rows.low[r] as number) * rowBytes;
    const lower = (rows.high[r] as number) * rowBytes;
    const wy = rows.weight[r] as number;
    const vy = 1 - wy;
    for (let c = 0; c < size; c++) {
      const wx = columns.weight[c] as number;
      const vx = 1 - wx;
      const l = left[c] as number;
      const h = right[c] as number;
      for (let ch = 0; ch < 3; ch++) {
        // top = I[y0, x0] (1 - wx) + I[y0, x1] wx; bottom likewise; top (1 - wy) + bottom wy.
        const top = (data[upper + l + ch] as number) * vx + (data[upper + h + ch] as number) * wx;
        const bottom =
          (data[lower + l + ch] as number) * vx + (data[lower + h + ch] as number) * wx;
        out[k++] = top * vy + bottom * wy;
      }
    }
  }
  return out;
}

/** Python's round(): halves go to the even neighbour. */
function roundHalfEven(value: number): number {
  const floor = Math.floor(value);
  const fraction = value - floor;
  if (fraction !== 0.5) return Math.round(value);
  return floor % 2 === 0 ? floor : floor + 1;
}

/** Intersection over union of two boxes, as runtime.py's `box_iou` (0 for an empty union). */
export function boxIou(a: readonly number[], b: readonly number[]): number {
  const [a0, a1, a2, a3] = a as Box;
  const [b0, b1, b2, b3] = b as Box;
  const x1 = Math.max(a0, b0);
  const y1 = Math.max(a1, b1);
  const x2 = Math.min(a2, b2);
  const y2 = Math.min(a3, b3);
  const inter = Math.max(x2 - x1, 0) * Math.max(y2 - y1, 0);
  const union = (a2 - a0) * (a3 - a1) + (b2 - b0) * (b3 - b1) - inter;
  return union > 0 ? inter / union : 0;
}

interface Candidate {
  row: number;
  box: Box;
  score: number;
  cls: string;
  sourceClass: string;
}

/**
 * The contract's decoding of the model's `detections` rows (flat, 6 per row) for a
 * width x height photo: runtime.py's `decode`. Rows at or above the threshold, boxes scaled to
 * the photo and clipped, classes mapped to NYU-40 (those mapped to null dropped), greedy NMS
 * per NYU-40 class (best score first, ties to the earlier row), boxes under MIN_BOX_PX on
 * either side dropped last.
 */
export function decodeDetections(
  raw: ArrayLike<number>,
  width: number,
  height: number,
  mapping: LabelMapping,
  scoreThreshold: number = SCORE_THRESHOLD,
): DetectedBox[] {
  if (raw.length % ROW !== 0) throw new Error(`expected rows of ${ROW} values, got ${raw.length}`);
  const { classes, toNyu40 } = mapping;
  const limits = [width, height, width, height];
  const scale = limits.map((v) => v / INPUT_SIZE);
  const kept: Candidate[] = [];
  for (let row = 0; row < raw.length / ROW; row++) {
    const at = row * ROW;
    const score = raw[at + 4] as number;
    const index = roundHalfEven(raw[at + 5] as number);
    if (!(score >= scoreThreshold) || !(index >= 0 && index < classes.length)) continue;
    const cls = toNyu40[index];
    if (cls === null || cls === undefined) continue;
    const box = [0, 1, 2, 3].map((k) =>
      Math.min(Math.max((raw[at + k] as number) * (scale[k] as number), 0), limits[k] as number),
    ) as Box;
    kept.push({ row, box, score, cls, sourceClass: classes[index] as string });
  }
  kept.sort((a, b) => (a.score === b.score ? a.row - b.row : b.score - a.score));
  const chosen: Candidate[] = [];
  for (const item of kept) {
    const suppressed = chosen.some((c) => c.cls === item.cls && boxIou(item.box, c.box) > NMS_IOU);
    if (!suppressed) chosen.push(item);
  }
  return chosen
    .filter(({ box }) => box[2] - box[0] >= MIN_BOX_PX && box[3] - box[1] >= MIN_BOX_PX)
    .map(({ box, score, cls, sourceClass }) => ({ bbox: box, score, cls, sourceClass }));
}

const NYU40 = new Set<string>(NYU40_CLASSES);

/** A detector's class mapping from its metadata (label_space + classes), as runtime.Detector. */
export function labelMapping(metadata: {
  label_space: string;
  classes: readonly string[];
}): LabelMapping {
  const classes = [...metadata.classes];
  if (classes.length === 0) throw new Error("the detector's metadata has no classes");
  let toNyu40: (string | null)[];
  if (metadata.label_space === "coco80") {
    toNyu40 = [...DETECTOR_MODEL.coco_to_nyu40];
  } else if (metadata.label_space === "nyu40") {
    const unknown = classes.filter((c) => !NYU40.has(c));
    if (unknown.length > 0) throw new Error(`detector classes not in NYU-40: ${unknown}`);
    toNyu40 = classes;
  } else {
    throw new Error(`unknown detector label space "${metadata.label_space}"`);
  }
  if (toNyu40.length !== classes.length) {
    throw new Error("the detector's class list does not match its label space");
  }
  return { classes, toNyu40 };
}
