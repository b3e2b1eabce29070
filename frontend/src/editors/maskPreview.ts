// A mask being drawn, shown live on the photo in place of the object's stored one: a canvas
// over the raster's window (liveLayer.ts), redrawn only where a stroke changed it, so a brush
// move costs a few rows of fillRect, not a new PNG of the whole mask.
import type { LiveLayer, Sheet } from "./liveLayer";
import { isEmptyRect, type MaskRaster, type PixelRect } from "./maskPainting";

const FALLBACK_COLOUR = "rgb(255, 255, 255)";

export class MaskPreview {
  private sheet: Sheet | null = null;
  private shownId: string | null = null;
  private raster: MaskRaster | null = null;
  private hidden: SVGElement | null = null;
  private colour = FALLBACK_COLOUR;

  constructor(
    private readonly svg: SVGSVGElement,
    private readonly layer: LiveLayer,
  ) {}

  /** The id of the object whose mask is shown, or null. */
  get objectId(): string | null {
    return this.shownId;
  }

  /** Whether `raster` is the one shown (a newer drawing may have taken its place). */
  showing(raster: MaskRaster): boolean {
    return this.raster === raster;
  }

  /** Show `raster` as `objectId`'s mask (its stored mask hidden meanwhile). */
  show(objectId: string, raster: MaskRaster): void {
    this.hide();
    const stored = this.hideStored(objectId);
    // Same colour as the object's mask, so painting looks like the mask growing.
    this.colour = stored?.dataset.colour ?? FALLBACK_COLOUR;
    this.sheet = this.layer.sheet(raster.window, {
      className: "mask-preview",
      testid: "mask-preview",
    });
    this.sheet.canvas.dataset.object = objectId;
    // As opaque as the stored mask of a selected object (the photo's opacity setting).
    if (stored) this.sheet.canvas.style.opacity = getComputedStyle(stored).opacity;
    this.shownId = objectId;
    this.raster = raster;
    // A new canvas is clear: only the set pixels' rows need drawing.
    const extent = raster.extent();
    if (extent) this.redraw(extent);
  }

  private hideStored(objectId: string): SVGElement | null {
    const stored = this.svg.querySelector<SVGElement>(
      `[data-testid="mask-${CSS.escape(objectId)}"]`,
    );
    if (this.hidden && this.hidden !== stored) this.hidden.style.visibility = "";
    if (stored) stored.style.visibility = "hidden";
    this.hidden = stored;
    return stored;
  }

  /** Draw the part of the raster in `rect` (photo pixels) again. */
  redraw(rect: PixelRect): void {
    const context = this.sheet?.context;
    const raster = this.raster;
    if (!context || !raster || isEmptyRect(rect)) return;
    const { left: ox, top: oy } = raster.window;
    const x0 = Math.max(rect.left, ox) - ox;
    const x1 = Math.min(rect.right, raster.window.right) - ox;
    const y0 = Math.max(rect.top, oy) - oy;
    const y1 = Math.min(rect.bottom, raster.window.bottom) - oy;
    if (x1 <= x0 || y1 <= y0) return;
    context.clearRect(x0, y0, x1 - x0, y1 - y0);
    context.fillStyle = this.colour;
    const { bits, width } = raster;
    for (let y = y0; y < y1; y++) {
      const row = y * width;
      let x = x0;
      while (x < x1) {
        while (x < x1 && bits[row + x] === 0) x++;
        const start = x;
        while (x < x1 && bits[row + x] === 1) x++;
        if (x > start) context.fillRect(start, y, x - start, 1);
      }
    }
  }

  /** Hide the stored mask again after the photo redrew its masks (a new revision came in). */
  keepStoredHidden(): void {
    if (this.shownId) this.hideStored(this.shownId);
  }

  /** Take the preview away; the object's stored mask shows again. */
  hide(): void {
    this.layer.remove(this.sheet);
    this.sheet = null;
    this.shownId = null;
    this.raster = null;
    if (this.hidden) this.hidden.style.visibility = "";
    this.hidden = null;
  }
}
