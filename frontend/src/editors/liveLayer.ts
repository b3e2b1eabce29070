// What the mask tools draw while the pointer moves (the mask being painted, the brush outline,
// refine strokes, a polygon being drawn), on HTML canvases laid over the photo's SVG in image
// pixels. Any change inside the SVG repaints all of it (photo, masks, arrows, labels), which
// takes tens of milliseconds without a GPU; a canvas of its own is repainted alone.
import { el } from "../dom";
import type { PixelRect } from "./maskPainting";

export interface Sheet {
  canvas: HTMLCanvasElement;
  context: CanvasRenderingContext2D | null;
  /** The photo pixels it covers, one canvas pixel each. */
  window: PixelRect;
}

export class LiveLayer {
  readonly element: HTMLDivElement;
  private readonly sheets = new Set<Sheet>();
  private readonly cursor: HTMLDivElement;
  // Image pixels to the layer's CSS pixels: x * scaleX + offsetX (the SVG is never rotated).
  private scaleX = 1;
  private scaleY = 1;
  private offsetX = 0;
  private offsetY = 0;

  constructor(private readonly svg: SVGSVGElement) {
    this.cursor = el("div", { className: "brush-cursor", testid: "brush-cursor" });
    this.cursor.hidden = true;
    this.element = el("div", { className: "live-layer" }, this.cursor);
    const parent = svg.parentElement;
    if (parent && getComputedStyle(parent).position === "static") {
      parent.style.position = "relative";
    }
    svg.after(this.element);
    this.place();
  }

  /** Follow the SVG's size, zoom and pan (call after any of them changed). */
  place(): void {
    const matrix = this.svg.getScreenCTM();
    const parent = this.svg.parentElement;
    if (!matrix || !parent) return;
    const box = this.svg.getBoundingClientRect();
    const outer = parent.getBoundingClientRect();
    Object.assign(this.element.style, {
      left: `${box.left - outer.left + parent.scrollLeft - parent.clientLeft}px`,
      top: `${box.top - outer.top + parent.scrollTop - parent.clientTop}px`,
      width: `${box.width}px`,
      height: `${box.height}px`,
    });
    this.scaleX = matrix.a;
    this.scaleY = matrix.d;
    this.offsetX = matrix.e - box.left;
    this.offsetY = matrix.f - box.top;
    for (const sheet of this.sheets) this.placeSheet(sheet);
  }

  /** A canvas over `window` (photo pixels); `remove` takes it away. */
  sheet(window: PixelRect, attrs: { className: string; testid: string }): Sheet {
    const canvas = el("canvas", {
      className: `live-sheet ${attrs.className}`,
      testid: attrs.testid,
      attrs: {
        width: Math.max(1, window.right - window.left),
        height: Math.max(1, window.bottom - window.top),
      },
    });
    const sheet = { canvas, context: canvas.getContext("2d"), window };
    this.sheets.add(sheet);
    this.element.insertBefore(canvas, this.cursor);
    this.placeSheet(sheet);
    return sheet;
  }

  remove(sheet: Sheet | null): void {
    if (!sheet) return;
    sheet.canvas.remove();
    this.sheets.delete(sheet);
  }

  /** The brush outline: a circle of `radius` image pixels at `at`, or none. */
  showCursor(at: readonly [number, number] | null, radius: number): void {
    this.cursor.hidden = at === null;
    if (!at) return;
    const width = 2 * radius * this.scaleX;
    const height = 2 * radius * this.scaleY;
    const x = at[0] * this.scaleX + this.offsetX - width / 2;
    const y = at[1] * this.scaleY + this.offsetY - height / 2;
    this.cursor.style.width = `${width}px`;
    this.cursor.style.height = `${height}px`;
    this.cursor.style.transform = `translate(${x}px, ${y}px)`;
  }

  dispose(): void {
    this.element.remove();
    this.sheets.clear();
  }

  private placeSheet({ canvas, window }: Sheet): void {
    const x = window.left * this.scaleX + this.offsetX;
    const y = window.top * this.scaleY + this.offsetY;
    canvas.style.transform = `matrix(${this.scaleX}, 0, 0, ${this.scaleY}, ${x}, ${y})`;
  }
}
