// The Relation Network's input tensors from a photo and its objects: the TypeScript twin of
// backend/src/holiscene/learning/preprocess.py (relation_inputs) and of the scene-to-objects
// step in learning/samples.py (object_masks, structural objects left out). The contract is in
// shared_schema/holiscene_schema/relation_model.py; the shared vectors
// (shared_schema/vectors/relation_model.json) hold both sides to the same numbers.
//
// Area resize of an H x W array to S x S: output cell (r, c) is the mean of the input rows
// floor(r H / S) .. max(floor((r + 1) H / S), floor(r H / S) + 1) - 1 and likewise the
// columns, summed in float64 and rounded once to float32.
import type { Mask, SceneObject } from "@holiscene/schema";
import { NYU40_CLASSES, RELATION_MODEL } from "@holiscene/schema";
import { isStructural } from "../state/supportGraph";

export const IMAGE_SIZE = RELATION_MODEL.image_size;
export const MASK_SIZE = RELATION_MODEL.mask_size;

/** Pixels row by row, 3 (RGB) or 4 (RGBA, e.g. a canvas's ImageData) bytes per pixel. */
export interface PixelImage {
  width: number;
  height: number;
  data: ArrayLike<number>;
}

/** What the model needs of one object. `mask` null: the object's 2D box stands in for it. */
export interface ObjectInput {
  cls: string;
  bbox: readonly [number, number, number, number];
  mask: Mask | null;
}

/** The contract's input tensors, flat, in the contract's shapes and dtypes. */
export interface RelationInputs {
  count: number; // N
  image: Float32Array; // [1, 3, IMAGE_SIZE, IMAGE_SIZE]
  masks: Float32Array; // [N, MASK_SIZE, MASK_SIZE]
  boxes: Float32Array; // [N, 4]
  classes: BigInt64Array; // [N]
}

/** Start (inclusive) and end (exclusive) input index of each output cell; never empty. */
export function cellBounds(
  length: number,
  cells: number,
): { starts: Int32Array; ends: Int32Array } {
  const starts = new Int32Array(cells);
  const ends = new Int32Array(cells);
  for (let i = 0; i < cells; i++) {
    const start = Math.floor((i * length) / cells);
    starts[i] = start;
    ends[i] = Math.min(Math.max(Math.floor(((i + 1) * length) / cells), start + 1), length);
  }
  return { starts, ends };
}

/**
 * Which cells hold each input index: `first[i]` .. `last[i]` (inclusive), a contiguous range
 * since the cells' bounds only grow. Downsizing gives each index one cell; upsizing repeats
 * an index over several.
 */
interface CellMap {
  starts: Int32Array;
  ends: Int32Array;
  first: Int32Array;
  last: Int32Array;
}

function cellMap(length: number, cells: number): CellMap {
  const { starts, ends } = cellBounds(length, cells);
  const first = new Int32Array(length).fill(cells);
  const last = new Int32Array(length).fill(-1);
  for (let c = 0; c < cells; c++) {
    for (let i = starts[c] as number; i < (ends[c] as number); i++) {
      if (c < (first[i] as number)) first[i] = c;
      last[i] = c;
    }
  }
  return { starts, ends, first, last };
}

/**
 * Sums of cells, accumulated row by row: `addRow(y, rowSums)` adds input row y's sums over each
 * column cell (channel fastest) into `rowSums`; rows outside [lo, hi) are zero. Returns each
 * cell's mean in float64, [cells][cells][channels].
 */
function cellMeans(
  rows: CellMap,
  columns: CellMap,
  channels: number,
  lo: number,
  hi: number,
  addRow: (y: number, rowSums: Float64Array) => void,
): Float64Array {
  const cells = rows.starts.length;
  const stride = cells * channels;
  const sums = new Float64Array(cells * stride);
  const rowSums = new Float64Array(stride);
  for (let y = Math.max(0, lo); y < Math.min(hi, rows.first.length); y++) {
    rowSums.fill(0);
    addRow(y, rowSums);
    for (let r = rows.first[y] as number; r <= (rows.last[y] as number); r++) {
      const base = r * stride;
      for (let k = 0; k < stride; k++)
        sums[base + k] = (sums[base + k] as number) + (rowSums[k] as number);
    }
  }
  for (let r = 0; r < cells; r++) {
    const height = (rows.ends[r] as number) - (rows.starts[r] as number);
    for (let c = 0; c < cells; c++) {
      const count = height * ((columns.ends[c] as number) - (columns.starts[c] as number));
      const base = r * stride + c * channels;
      for (let ch = 0; ch < channels; ch++) sums[base + ch] = (sums[base + ch] as number) / count;
    }
  }
  return sums;
}

/**
 * Area resize of an (H, W, C) array (row by row, channel fastest) to size x size, as float32
 * [size][size][C]: preprocess.py's `area_resize`.
 */
export function areaResize(
  values: ArrayLike<number>,
  height: number,
  width: number,
  channels: number,
  size: number,
): Float32Array {
  const columns = cellMap(width, size);
  const means = cellMeans(cellMap(height, size), columns, channels, 0, height, (y, rowSums) => {
    for (let x = 0; x < width; x++) {
      for (let c = columns.first[x] as number; c <= (columns.last[x] as number); c++) {
        for (let ch = 0; ch < channels; ch++) {
          const k = c * channels + ch;
          rowSums[k] = (rowSums[k] as number) + (values[(y * width + x) * channels + ch] as number);
        }
      }
    }
  });
  return Float32Array.from(means);
}

/** v / 255 in float64 for each byte value v. */
const SHARE = Float64Array.from({ length: 256 }, (_, v) => v / 255);

/** The model's `image`: RGB / 255, area-resized, channels first ([3][S][S]). */
export function imageTensor(image: PixelImage): Float32Array {
  const { width, height, data } = image;
  const stride = data.length / (width * height);
  if (stride !== 3 && stride !== 4) {
    throw new Error(`expected 3 or 4 bytes per pixel for ${width}x${height}, got ${data.length}`);
  }
  const size = IMAGE_SIZE;
  const columns = cellMap(width, size);
  const { first, last } = columns;
  const means = cellMeans(cellMap(height, size), columns, 3, 0, height, (y, rowSums) => {
    let at = y * width * stride;
    for (let x = 0; x < width; x++, at += stride) {
      // As preprocess.py: each channel value divided by 255 in float64, then summed.
      const red = SHARE[data[at] as number] as number;
      const green = SHARE[data[at + 1] as number] as number;
      const blue = SHARE[data[at + 2] as number] as number;
      const lastCell = last[x] as number;
      for (let c = first[x] as number; c <= lastCell; c++) {
        const k = 3 * c;
        rowSums[k] = (rowSums[k] as number) + red;
        rowSums[k + 1] = (rowSums[k + 1] as number) + green;
        rowSums[k + 2] = (rowSums[k + 2] as number) + blue;
      }
    }
  });
  const plane = size * size;
  const tensor = new Float32Array(3 * plane);
  for (let i = 0; i < plane; i++) {
    tensor[i] = means[3 * i] as number;
    tensor[plane + i] = means[3 * i + 1] as number;
    tensor[2 * plane + i] = means[3 * i + 2] as number;
  }
  return tensor;
}

/** Python's round(): halves go to the even neighbour. */
export function roundHalfEven(value: number): number {
  const floor = Math.floor(value);
  const fraction = value - floor;
  if (fraction !== 0.5) return Math.round(value);
  return floor % 2 === 0 ? floor : floor + 1;
}

/** The runs of mask pixels of one object, as [x0, x1) segments of image rows. */
export interface Segments {
  /** Segments of row y are `spans[offsets[y - top]] .. spans[offsets[y - top + 1]]`, pairs. */
  top: number;
  offsets: Int32Array;
  spans: Int32Array;
}

/** Mask pixels row by row: the decoded RLE (pixels beyond the image dropped), or the box
 * rounded to pixels (at least one pixel each way), as samples.py's `object_masks`. */
export function maskSegments(
  object: ObjectInput,
  imageWidth: number,
  imageHeight: number,
): Segments {
  const mask = object.mask;
  if (!mask) {
    const [bx0, by0, bx1, by1] = object.bbox.map(roundHalfEven) as [number, number, number, number];
    const clamp = (v: number, hi: number) => Math.min(Math.max(v, 0), hi);
    const x0 = clamp(bx0, imageWidth);
    const x1 = clamp(Math.max(bx0 + 1, bx1), imageWidth);
    const top = clamp(by0, imageHeight);
    const rows = Math.max(0, clamp(Math.max(by0 + 1, by1), imageHeight) - top);
    const offsets = Int32Array.from({ length: rows + 1 }, (_, i) => (x1 > x0 ? 2 * i : 0));
    const spans = new Int32Array(2 * rows);
    for (let i = 0; i < rows; i++) spans.set([x0, x1], 2 * i);
    return { top, offsets, spans };
  }
  const [ox, oy] = mask.origin;
  const [width, height] = mask.size;
  const total = width * height;
  const rows = Math.max(0, Math.min(height, imageHeight - oy));
  const right = Math.min(width, imageWidth - ox); // window columns inside the image
  const perRow: number[][] = Array.from({ length: rows }, () => []);
  let at = 0;
  for (let i = 0; i < mask.rle.length && at < total; i++) {
    const end = Math.min(at + (mask.rle[i] as number), total);
    if (i % 2 === 1) {
      for (let p = at; p < end; ) {
        const row = Math.floor(p / width);
        const rowEnd = Math.min(end, (row + 1) * width);
        const a = p - row * width;
        const b = Math.min(rowEnd - row * width, right);
        if (row < rows && a < b) (perRow[row] as number[]).push(ox + a, ox + b);
        p = rowEnd;
      }
    }
    at = end;
  }
  const offsets = new Int32Array(rows + 1);
  const spans = new Int32Array(perRow.reduce((n, list) => n + list.length, 0));
  let n = 0;
  perRow.forEach((list, row) => {
    spans.set(list, n);
    n += list.length;
    offsets[row + 1] = n;
  });
  return { top: oy, offsets, spans };
}

/** The model's `masks` row of one object: the share of mask pixels in each cell. */
function maskTensor(segments: Segments, rows: CellMap, columns: CellMap): Float64Array {
  const { top, offsets, spans } = segments;
  const { starts, ends, first, last } = columns;
  const bottom = top + offsets.length - 1;
  return cellMeans(rows, columns, 1, top, bottom, (y, rowSums) => {
    for (let k = offsets[y - top] as number; k < (offsets[y - top + 1] as number); k += 2) {
      const a = spans[k] as number;
      const b = spans[k + 1] as number;
      for (let c = first[a] as number; c <= (last[b - 1] as number); c++) {
        const overlap = Math.min(b, ends[c] as number) - Math.max(a, starts[c] as number);
        rowSums[c] = (rowSums[c] as number) + overlap;
      }
    }
  });
}

const CLASS_INDEX = new Map<string, number>(NYU40_CLASSES.map((name, i) => [name, i]));

/** The class's index in NYU40_CLASSES (the model's `classes` entry). */
export function classIndex(cls: string): number {
  const index = CLASS_INDEX.get(cls);
  if (index === undefined) throw new Error(`"${cls}" is not an NYU-40 class`);
  return index;
}

/** The contract's input tensors: preprocess.py's `relation_inputs`. */
export function relationInputs(image: PixelImage, objects: readonly ObjectInput[]): RelationInputs {
  if (objects.length === 0) throw new Error("the Relation Network needs at least one object");
  const { width, height } = image;
  const count = objects.length;
  const plane = MASK_SIZE * MASK_SIZE;
  const masks = new Float32Array(count * plane);
  const boxes = new Float32Array(count * 4);
  const classes = new BigInt64Array(count);
  const scale = [width, height, width, height];
  const rows = cellMap(height, MASK_SIZE);
  const columns = cellMap(width, MASK_SIZE);
  objects.forEach((object, i) => {
    masks.set(maskTensor(maskSegments(object, width, height), rows, columns), i * plane);
    object.bbox.forEach((v, k) => {
      boxes[i * 4 + k] = v / (scale[k] as number);
    });
    classes[i] = BigInt(classIndex(object.cls));
  });
  return { count, image: imageTensor(image), masks, boxes, classes };
}

/** The objects the model scores: every object but structural ones (a labelled wall or floor). */
export function modelObjects(objects: readonly SceneObject[]): SceneObject[] {
  return objects.filter((o) => !isStructural(o.class));
}

/** The scene's model inputs, objects in `modelObjects` order. */
export function sceneInputs(image: PixelImage, objects: readonly SceneObject[]): RelationInputs {
  return relationInputs(image, objectInputs(objects));
}

/** What the model (and the support geometry) reads of the scene's objects, in its order. */
export function objectInputs(objects: readonly SceneObject[]): ObjectInput[] {
  return modelObjects(objects).map((o) => ({ cls: o.class, bbox: o.bbox, mask: o.mask ?? null }));
}
