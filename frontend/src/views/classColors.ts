// One colour per NYU-40 class: the masks, the object list and the 3D view use it when colouring
// by class (objectColors.ts colours by object, the default).
import { NYU40_CLASSES } from "@holiscene/schema";

export type Rgb = readonly [number, number, number];

export function hslToRgb(h: number, s: number, l: number): Rgb {
  const a = s * Math.min(l, 1 - l);
  const channel = (n: number) => {
    const k = (n + h / 30) % 12;
    return Math.round(255 * (l - a * Math.max(-1, Math.min(k - 3, 9 - k, 1))));
  };
  return [channel(0), channel(8), channel(4)];
}

const GOLDEN_ANGLE = 137.508;

/** The class's colour as 0..255 RGB; classes far apart in hue (golden-angle steps). */
export function classRgb(cls: string): Rgb {
  const index = (NYU40_CLASSES as readonly string[]).indexOf(cls);
  if (index < 0) return [128, 128, 128];
  return hslToRgb((index * GOLDEN_ANGLE) % 360, 0.7, 0.52);
}

/** A colour as CSS, with an alpha when below 1. */
export function rgbCss([r, g, b]: Rgb, alpha = 1): string {
  return alpha === 1 ? `rgb(${r} ${g} ${b})` : `rgb(${r} ${g} ${b} / ${alpha})`;
}

export function classCss(cls: string, alpha = 1): string {
  return rgbCss(classRgb(cls), alpha);
}

/** A colour as a 0xRRGGBB number (three.js). */
export const rgbHex = ([r, g, b]: Rgb): number => (r << 16) | (g << 8) | b;

/** The class's colour as a 0xRRGGBB number (three.js). */
export function classHex(cls: string): number {
  return rgbHex(classRgb(cls));
}
