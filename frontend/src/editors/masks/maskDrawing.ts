// What the mask tools share: the photo's live layer and the mask preview, the brush size, the
// status line, which object a press draws on, the mask a drawing starts from, and saving a
// drawn mask as one set_mask edit (objectEditor.apply: one revision, undoable).
import type { SceneObject } from "@holiscene/schema";
import { el } from "../../dom";
import { classText } from "../../state/classNames";
import type { SceneSession } from "../../state/sceneSession";
import { LiveLayer } from "../liveLayer";
import { MaskRaster, type PixelRect } from "../maskPainting";
import { MaskPreview } from "../maskPreview";
import { type ImagePoint, type PhotoToolHost, toolHint } from "../photoTools";
import { BrushSize } from "./brushSize";

const NEED_OBJECT = "Select an object first (click it on the photo or in the list).";

export class MaskDrawing {
  readonly session: SceneSession;
  /** The whole photo, in photo pixels. */
  readonly photo: PixelRect;
  readonly live: LiveLayer;
  readonly preview: MaskPreview;
  readonly brush = new BrushSize();
  readonly status = el("span", {
    className: "mask-tool-status",
    testid: "mask-tool-status",
    attrs: { role: "status" },
  });
  // The mask drawn last but maybe not yet adopted from the server: the next stroke on the same
  // object starts from it, so quick strokes do not undo each other.
  pending: { objectId: string; raster: MaskRaster } | null = null;
  private cursorAt: ImagePoint | null = null;

  constructor(readonly host: PhotoToolHost) {
    this.session = host.session;
    this.photo = { left: 0, top: 0, right: host.width, bottom: host.height };
    this.live = new LiveLayer(host.svg);
    this.preview = new MaskPreview(host.svg, this.live);
    this.brush.onChange(() => this.placeCursor(this.cursorAt));
    // The status keeps one line (the photo must not move); a click shows a long one whole.
    this.status.addEventListener("click", () => this.status.classList.toggle("is-expanded"));
  }

  /** Say something in the tools' status line (an error in red). */
  say(text: string, error = false): void {
    if (this.status.textContent !== text) this.status.classList.remove("is-expanded");
    this.status.textContent = text;
    this.status.title = text; // the line may cut it short
    this.status.classList.toggle("is-error", error);
  }

  /** The object to draw on; with none selected, a press on an object selects it instead. */
  pick(event: PointerEvent): SceneObject | null {
    const object = this.session.selectedObject;
    if (object) return object;
    const under = this.host.objectAt(event);
    if (under) {
      this.session.select(under);
      this.say(`Selected ${under}: now draw on its mask.`);
    } else this.say(NEED_OBJECT, true);
    return null;
  }

  /** Say whose mask the tools draw on (or that one must be selected). */
  readonly describeTarget = (): void => {
    const object = this.session.selectedObject;
    this.say(object ? `Mask of ${classText(object.class)} ${object.id}` : NEED_OBJECT, !object);
  };

  /** What the object's mask is now, as a raster over the photo (its box when it has none). */
  startingRaster(object: SceneObject): MaskRaster {
    if (this.pending?.objectId === object.id) return this.pending.raster.copy();
    if (object.mask) return MaskRaster.fromMask(object.mask, this.photo);
    const raster = new MaskRaster(this.photo);
    const [x1, y1, x2, y2] = object.bbox;
    raster.fillPolygon(
      [
        [x1, y1],
        [x2, y1],
        [x2, y2],
        [x1, y2],
      ],
      1,
    );
    return raster;
  }

  /** Send the drawn mask as one set_mask edit; the preview stays until the answer is in. */
  async save(objectId: string, raster: MaskRaster, label: string): Promise<void> {
    const { preview } = this;
    const mask = raster.toMask("manual");
    if (!mask) {
      preview.hide();
      this.pending = null;
      this.say(
        "That would leave no mask at all: to take the object away, remove it instead.",
        true,
      );
      return;
    }
    const object = this.session.object(objectId);
    if (object && raster.samePixels(this.startingRaster(object))) {
      // A stroke over pixels the mask already had (or never had): no revision for nothing,
      // whoever made the mask (GrabCut's stays GrabCut's).
      preview.hide();
      // The label is written for the middle of a sentence ("Undo eraser o0's mask").
      this.say(`${label.charAt(0).toUpperCase()}${label.slice(1)}: the mask is unchanged.`);
      return;
    }
    this.pending = { objectId, raster };
    const saved = await this.host.objects.apply([{ kind: "set_mask", id: objectId, mask }], label);
    if (this.pending?.raster === raster) this.pending = null;
    if (!saved) this.say(`${label}: not saved (see the message above the photo).`, true);
    // A newer drawing, begun on this one, may be on screen already: it stays.
    if (!preview.showing(raster)) return;
    preview.hide();
    if (saved) this.describeTarget();
  }

  /** The brush's outline at a point of the photo (none: null). */
  placeCursor(at: ImagePoint | null): void {
    this.cursorAt = at;
    this.live.showCursor(at, this.brush.radius);
  }

  /** The tool's options: the brush size (if it has one) and the status line, then the hint.
   *  Two lines at most at a laptop's width: the sticky toolbar covers the photo's top. */
  options(hint: string, withSize: boolean): () => HTMLElement {
    return () =>
      el(
        "span",
        { className: "mask-tool-options" },
        el(
          "span",
          { className: "mask-tool-controls" },
          withSize ? this.brush.element : null,
          this.status,
        ),
        toolHint(hint),
      );
  }
}
