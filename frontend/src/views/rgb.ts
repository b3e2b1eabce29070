// Colours as 0..255 RGB triples, and their CSS and three.js forms.

export type Rgb = readonly [number, number, number];

export function hslToRgb(h: number, s: number, l: number): Rgb {
  const a = s * Math.min(l, 1 - l);
  const channel = (n: number) => {
    const k = (n + h / 30) % 12;
    return Math.round(255 * (l - a * Math.max(-1, Math.min(k - 3, 9 - k, 1))));
  };
  return [channel(0), channel(8), channel(4)];
}

/** A colour as CSS, with an alpha when below 1. */
export function rgbCss([r, g, b]: Rgb, alpha = 1): string {
  return alpha === 1 ? `rgb(${r} ${g} ${b})` : `rgb(${r} ${g} ${b} / ${alpha})`;
}

/** A colour as a 0xRRGGBB number (three.js). */
export const rgbHex = ([r, g, b]: Rgb): number => (r << 16) | (g << 8) | b;
