// Reading what a WebGL canvas shows (it renders with preserveDrawingBuffer).
import type { Locator } from "@playwright/test";

export interface CanvasColours {
  width: number;
  height: number;
  /** Distinct colours, each channel quantised to 16 levels. */
  distinct: number;
  /** Share of pixels that differ from the most common colour. */
  nonBackground: number;
}

export function canvasColours(canvas: Locator): Promise<CanvasColours> {
  return canvas.evaluate((node) => {
    const source = node as HTMLCanvasElement;
    const copy = document.createElement("canvas");
    copy.width = source.width;
    copy.height = source.height;
    const context = copy.getContext("2d");
    if (!context) throw new Error("no 2D context");
    context.drawImage(source, 0, 0);
    const { data } = context.getImageData(0, 0, copy.width, copy.height);
    const counts = new Map<number, number>();
    // One RGBA pixel per 32-bit word; keep the top 4 bits of R, G and B.
    for (const pixel of new Uint32Array(data.buffer)) {
      const key = pixel & 0x00f0f0f0;
      counts.set(key, (counts.get(key) ?? 0) + 1);
    }
    const pixels = data.length / 4;
    const mostCommon = Math.max(...counts.values());
    return {
      width: copy.width,
      height: copy.height,
      distinct: counts.size,
      nonBackground: (pixels - mostCommon) / pixels,
    };
  });
}
