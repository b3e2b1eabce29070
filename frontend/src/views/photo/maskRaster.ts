// Masks: run-length decoding, tinted images for the overlay, centroids and a hit map.
import type { Mask, SceneObject } from "@holiscene/schema";
import type { Rgb } from "../classColors";

/** Each run of inside pixels of a mask's window: [start, end) in row-major pixel indices. */
function insideRuns(mask: Mask, each: (start: number, end: number) => void): void {
  const total = mask.size[0] * mask.size[1];
  let at = 0;
  mask.rle.forEach((run, i) => {
    const end = Math.min(at + run, total);
    if (i % 2 === 1 && end > at) each(at, end);
    at = end;
  });
}

/** The mask's window as one byte per pixel (1 inside), row by row. */
export function decodeMask(mask: Mask): Uint8Array {
  const bits = new Uint8Array(mask.size[0] * mask.size[1]);
  insideRuns(mask, (start, end) => bits.fill(1, start, end));
  return bits;
}

/** The canvas every mask image is encoded on (a new canvas and context cost ms each). */
let encoder: { canvas: HTMLCanvasElement; context: CanvasRenderingContext2D | null } | null = null;

/** A PNG data URL of the mask's window: the colour inside, transparent outside. */
export function maskImageUrl(mask: Mask, [r, g, b]: Rgb): string {
  const [width, height] = mask.size;
  if (!encoder) {
    const canvas = document.createElement("canvas");
    // A canvas kept in main memory: encoding a GPU-backed one waits for a read-back, 10-190
    // ms per mask in headless Chromium, most of an object edit's redraw.
    encoder = { canvas, context: canvas.getContext("2d", { willReadFrequently: true }) };
  }
  const { canvas, context } = encoder;
  // Setting the size clears the canvas.
  canvas.width = Math.max(1, width);
  canvas.height = Math.max(1, height);
  if (!context || width === 0 || height === 0) return canvas.toDataURL();
  const image = context.createImageData(width, height);
  // One 32-bit write per pixel, a run at a time (ImageData is RGBA in memory order; every
  // browser this runs in is little-endian, so the word is ABGR).
  const pixels = new Uint32Array(image.data.buffer);
  const colour = ((255 << 24) | (b << 16) | (g << 8) | r) >>> 0;
  insideRuns(mask, (start, end) => pixels.fill(colour, start, end));
  context.putImageData(image, 0, 0);
  return canvas.toDataURL("image/png");
}

export interface Region {
  /** Pixels inside (the box's area when there is no mask). */
  area: number;
  /** Centre of mass of the mask, or the box's centre. */
  centroid: [number, number];
  /** Decoded mask bits, or null when the object has no mask. */
  bits: Uint8Array | null;
}

/** Where an object is in the image: its mask if it has one, else its box. */
export function objectRegion(object: SceneObject): Region {
  const [x1, y1, x2, y2] = object.bbox;
  const boxRegion: Region = {
    area: Math.max(1, (x2 - x1) * (y2 - y1)),
    centroid: [(x1 + x2) / 2, (y1 + y2) / 2],
    bits: null,
  };
  const mask = object.mask;
  if (!mask) return boxRegion;
  const bits = decodeMask(mask);
  const [width] = mask.size;
  const [ox, oy] = mask.origin;
  let area = 0;
  let sumX = 0;
  let sumY = 0;
  // Summed a row's piece of a run at a time (a run may wrap onto the next rows).
  insideRuns(mask, (start, end) => {
    for (let at = start; at < end; ) {
      const row = Math.floor(at / width);
      const column = at - row * width;
      const length = Math.min(end - at, width - column);
      area += length;
      sumX += length * column + (length * (length - 1)) / 2;
      sumY += length * row;
      at += length;
    }
  });
  if (area === 0) return { ...boxRegion, bits };
  return { area, centroid: [ox + sumX / area + 0.5, oy + sumY / area + 0.5], bits };
}

const HIT_MAP_MAX_SIDE = 1024;

export interface Placed {
  object: SceneObject;
  region: Region;
}

/** Which object is at an image point; smaller objects lie on top of larger ones. */
export class HitMap {
  private readonly cells: Int32Array;
  private readonly scale: number;
  private readonly columns: number;
  private readonly rows: number;
  private readonly ids: string[];

  constructor(width: number, height: number, placed: readonly Placed[]) {
    this.scale = Math.min(1, HIT_MAP_MAX_SIDE / Math.max(width, height));
    this.columns = Math.max(1, Math.round(width * this.scale));
    this.rows = Math.max(1, Math.round(height * this.scale));
    this.cells = new Int32Array(this.columns * this.rows).fill(-1);
    this.ids = placed.map((p) => p.object.id);
    const largestFirst = placed
      .map((p, index) => ({ ...p, index }))
      .sort((a, b) => b.region.area - a.region.area);
    for (const { object, region, index } of largestFirst) this.paint(index, object, region);
  }

  /** The id of the object at image point (x, y), or null. */
  at(x: number, y: number): string | null {
    const column = Math.floor(x * this.scale);
    const row = Math.floor(y * this.scale);
    if (column < 0 || row < 0 || column >= this.columns || row >= this.rows) return null;
    const index = this.cells[row * this.columns + column] ?? -1;
    return index >= 0 ? (this.ids[index] ?? null) : null;
  }

  private paint(index: number, object: SceneObject, region: Region): void {
    const mask = object.mask;
    const [left, top, right, bottom] = mask
      ? [
          mask.origin[0],
          mask.origin[1],
          mask.origin[0] + mask.size[0],
          mask.origin[1] + mask.size[1],
        ]
      : object.bbox;
    if (mask && region.bits && this.scale === 1) {
      this.paintBits(index, mask, region.bits);
      return;
    }
    const c0 = Math.max(0, Math.floor(left * this.scale));
    const c1 = Math.min(this.columns, Math.ceil(right * this.scale));
    const r0 = Math.max(0, Math.floor(top * this.scale));
    const r1 = Math.min(this.rows, Math.ceil(bottom * this.scale));
    for (let row = r0; row < r1; row++) {
      for (let column = c0; column < c1; column++) {
        if (mask && region.bits) {
          const x = Math.floor((column + 0.5) / this.scale) - mask.origin[0];
          const y = Math.floor((row + 0.5) / this.scale) - mask.origin[1];
          if (x < 0 || y < 0 || x >= mask.size[0] || y >= mask.size[1]) continue;
          if (!region.bits[y * mask.size[0] + x]) continue;
        }
        this.cells[row * this.columns + column] = index;
      }
    }
  }

  /** A mask at full resolution: its inside pixels, row by row. */
  private paintBits(index: number, mask: Mask, bits: Uint8Array): void {
    const [width, height] = mask.size;
    const [ox, oy] = mask.origin;
    const c0 = Math.max(0, -ox);
    const c1 = Math.min(width, this.columns - ox);
    for (let y = Math.max(0, -oy); y < Math.min(height, this.rows - oy); y++) {
      const from = y * width;
      const to = (oy + y) * this.columns + ox;
      for (let x = c0; x < c1; x++) if (bits[from + x]) this.cells[to + x] = index;
    }
  }
}
