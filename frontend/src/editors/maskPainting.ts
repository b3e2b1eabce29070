// A mask being drawn by hand: one byte per pixel over a window of the photo, painted with a
// round brush (in or out) or a filled polygon, read from and written back to the contract's
// run-length Mask. A pixel belongs to a shape when its centre (x + 0.5, y + 0.5) does, so a
// stroke and the server's GrabCut agree on which pixels a point covers.
import type { Mask } from "@holiscene/schema";
import { decodeMask } from "../views/photo/maskRaster";

export type Point = readonly [number, number];

/** A rectangle of pixels: columns left..right-1, rows top..bottom-1 (photo coordinates). */
export interface PixelRect {
  left: number;
  top: number;
  right: number;
  bottom: number;
}

export const isEmptyRect = (r: PixelRect) => r.right <= r.left || r.bottom <= r.top;

/** The smallest rectangle holding both. */
export function unionRect(a: PixelRect | null, b: PixelRect): PixelRect {
  if (!a || isEmptyRect(a)) return b;
  if (isEmptyRect(b)) return a;
  return {
    left: Math.min(a.left, b.left),
    top: Math.min(a.top, b.top),
    right: Math.max(a.right, b.right),
    bottom: Math.max(a.bottom, b.bottom),
  };
}

// Below this a brush would fall between pixel centres and paint nothing.
const MIN_RADIUS = Math.SQRT1_2;

export class MaskRaster {
  readonly bits: Uint8Array;

  /** An empty raster over `window` (photo pixels). */
  constructor(readonly window: PixelRect) {
    this.bits = new Uint8Array(this.width * this.height);
  }

  get width(): number {
    return Math.max(0, this.window.right - this.window.left);
  }

  get height(): number {
    return Math.max(0, this.window.bottom - this.window.top);
  }

  /** A raster over `window` holding a stored mask (its pixels outside the window dropped). */
  static fromMask(mask: Mask | null | undefined, window: PixelRect): MaskRaster {
    const raster = new MaskRaster(window);
    if (!mask) return raster;
    const decoded = decodeMask(mask);
    const [maskWidth, maskHeight] = mask.size;
    const [ox, oy] = mask.origin;
    const area = raster.clip({ left: ox, top: oy, right: ox + maskWidth, bottom: oy + maskHeight });
    for (let y = area.top; y < area.bottom; y++) {
      const from = (y - oy) * maskWidth + (area.left - ox);
      raster.bits.set(
        decoded.subarray(from, from + area.right - area.left),
        raster.index(area.left, y),
      );
    }
    return raster;
  }

  /** Whether the photo pixel (x, y) is set. */
  has(x: number, y: number): boolean {
    const { left, top, right, bottom } = this.window;
    if (x < left || y < top || x >= right || y >= bottom) return false;
    return this.bits[this.index(x, y)] === 1;
  }

  /** How many pixels are set. */
  count(): number {
    let total = 0;
    for (const bit of this.bits) total += bit;
    return total;
  }

  /** Whether `other` covers the same window with the same pixels set. */
  samePixels(other: MaskRaster): boolean {
    const [a, b] = [this.window, other.window];
    if (a.left !== b.left || a.top !== b.top || a.right !== b.right || a.bottom !== b.bottom)
      return false;
    return this.bits.every((bit, i) => bit === other.bits[i]);
  }

  copy(): MaskRaster {
    const copy = new MaskRaster(this.window);
    copy.bits.set(this.bits);
    return copy;
  }

  /**
   * Paint a round brush of `radius` along the polyline through `points` (a single point is a
   * dot): set the pixels it covers to `value`. Returns the rectangle that may have changed.
   */
  paintStroke(points: readonly Point[], radius: number, value: 0 | 1): PixelRect {
    const r = Math.max(radius, MIN_RADIUS);
    let changed: PixelRect | null = null;
    points.forEach((point, i) => {
      const from = i === 0 ? point : (points[i - 1] as Point);
      changed = unionRect(changed, this.paintSegment(from, point, r, value));
    });
    return changed ?? { left: 0, top: 0, right: 0, bottom: 0 };
  }

  /** Set the pixels inside the polygon (even-odd rule) to `value`; returns where. */
  fillPolygon(points: readonly Point[], value: 0 | 1): PixelRect {
    const none = { left: 0, top: 0, right: 0, bottom: 0 };
    if (points.length < 3) return none;
    const xs = points.map((p) => p[0]);
    const ys = points.map((p) => p[1]);
    const area = this.clip({
      left: Math.floor(Math.min(...xs)),
      top: Math.floor(Math.min(...ys)),
      right: Math.ceil(Math.max(...xs)),
      bottom: Math.ceil(Math.max(...ys)),
    });
    if (isEmptyRect(area)) return none;
    const crossings: number[] = [];
    for (let y = area.top; y < area.bottom; y++) {
      const cy = y + 0.5;
      crossings.length = 0;
      points.forEach((a, i) => {
        const b = points[(i + 1) % points.length] as Point;
        // Half-open in y, so a vertex on the scan line is counted once.
        if (a[1] <= cy === b[1] <= cy) return;
        crossings.push(a[0] + ((cy - a[1]) / (b[1] - a[1])) * (b[0] - a[0]));
      });
      crossings.sort((p, q) => p - q);
      for (let k = 0; k + 1 < crossings.length; k += 2) {
        // Pixels whose centre lies between the two crossings.
        const x0 = Math.max(area.left, Math.ceil((crossings[k] as number) - 0.5));
        const x1 = Math.min(area.right, Math.ceil((crossings[k + 1] as number) - 0.5));
        if (x1 > x0) this.bits.fill(value, this.index(x0, y), this.index(x1, y));
      }
    }
    return area;
  }

  /** The set pixels' bounding rectangle, or null when none is set. */
  extent(): PixelRect | null {
    const { width, height } = this;
    let left = width;
    let right = -1;
    let top = -1;
    let bottom = -1;
    for (let y = 0; y < height; y++) {
      const row = this.bits.subarray(y * width, (y + 1) * width);
      const first = row.indexOf(1);
      if (first < 0) continue;
      if (top < 0) top = y;
      bottom = y;
      left = Math.min(left, first);
      right = Math.max(right, row.lastIndexOf(1));
    }
    if (top < 0) return null;
    const { left: ox, top: oy } = this.window;
    return { left: ox + left, top: oy + top, right: ox + right + 1, bottom: oy + bottom + 1 };
  }

  /**
   * The contract's Mask of the set pixels: its window cropped to them, runs alternating 0 and
   * 1 from a run of 0, row by row. Null when no pixel is set (a mask cannot be empty).
   */
  toMask(source: Mask["source"] = "manual"): Mask | null {
    const extent = this.extent();
    if (!extent) return null;
    const rle: number[] = [];
    let current = 0;
    let run = 0;
    for (let y = extent.top; y < extent.bottom; y++) {
      const start = this.index(extent.left, y);
      for (let i = start; i < start + extent.right - extent.left; i++) {
        const bit = this.bits[i] as number;
        if (bit === current) {
          run += 1;
          continue;
        }
        rle.push(run);
        current = bit;
        run = 1;
      }
    }
    rle.push(run);
    return {
      origin: [extent.left, extent.top],
      size: [extent.right - extent.left, extent.bottom - extent.top],
      rle,
      source,
    };
  }

  private index(x: number, y: number): number {
    return (y - this.window.top) * this.width + (x - this.window.left);
  }

  private clip(rect: PixelRect): PixelRect {
    const w = this.window;
    return {
      left: Math.max(w.left, rect.left),
      top: Math.max(w.top, rect.top),
      right: Math.min(w.right, rect.right),
      bottom: Math.min(w.bottom, rect.bottom),
    };
  }

  private paintSegment(a: Point, b: Point, r: number, value: 0 | 1): PixelRect {
    const area = this.clip({
      left: Math.floor(Math.min(a[0], b[0]) - r),
      top: Math.floor(Math.min(a[1], b[1]) - r),
      right: Math.ceil(Math.max(a[0], b[0]) + r),
      bottom: Math.ceil(Math.max(a[1], b[1]) + r),
    });
    const dx = b[0] - a[0];
    const dy = b[1] - a[1];
    const length2 = dx * dx + dy * dy;
    const r2 = r * r;
    for (let y = area.top; y < area.bottom; y++) {
      const py = y + 0.5 - a[1];
      let rowStart = this.index(area.left, y);
      for (let x = area.left; x < area.right; x++, rowStart++) {
        const px = x + 0.5 - a[0];
        // The nearest point of the segment to the pixel's centre.
        const t = length2 > 0 ? Math.min(1, Math.max(0, (px * dx + py * dy) / length2)) : 0;
        const ex = px - t * dx;
        const ey = py - t * dy;
        if (ex * ex + ey * ey <= r2) this.bits[rowStart] = value;
      }
    }
    return area;
  }
}
