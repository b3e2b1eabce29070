// Masks: run-length decoding, path data for the overlay, centroids and a hit map.
import type { Mask, SceneObject } from "@holiscene/schema";

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

/**
 * The mask's inside pixels as SVG path data in image pixels: one rectangle per run of a row,
 * rows that repeat the row above growing its rectangles instead. Drawn as a path, a mask needs
 * no image to be encoded (a canvas's PNG, about 1 ms a mask) and decoded before it shows.
 */
export function maskPathData(mask: Mask): string {
  const [width] = mask.size;
  const [ox, oy] = mask.origin;
  const parts: string[] = [];
  let block: number[] = []; // [start, end) columns of each run of the rows being grown
  let blockTop = 0;
  let blockRows = 0;
  const flush = () => {
    for (let i = 0; i < block.length; i += 2) {
      const start = block[i] ?? 0;
      const length = (block[i + 1] ?? 0) - start;
      parts.push(`M${ox + start} ${oy + blockTop}h${length}v${blockRows}h${-length}z`);
    }
  };
  let row: number[] = [];
  let rowIndex = 0;
  const endRow = () => {
    const same = row.length === block.length && row.every((v, i) => v === block[i]);
    if (same && blockRows > 0) blockRows += 1;
    else {
      flush();
      block = row;
      blockTop = rowIndex;
      blockRows = 1;
    }
    row = [];
    rowIndex += 1;
  };
  insideRuns(mask, (start, end) => {
    for (let at = start; at < end; ) {
      const y = Math.floor(at / width);
      while (rowIndex < y) endRow();
      const column = at - y * width;
      const length = Math.min(end - at, width - column);
      row.push(column, column + length);
      at += length;
    }
  });
  endRow();
  flush();
  return parts.join("");
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
