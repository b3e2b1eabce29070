// Brush and Eraser: paint the selected object's mask in (1) or out (0); the stroke is saved
// when the pointer is released.
import type { MaskRaster } from "../maskPainting";
import type { ImagePoint, PhotoTool } from "../photoTools";
import type { MaskDrawing } from "./maskDrawing";

export interface StrokeToolSpec {
  id: string;
  label: string;
  key: string;
  /** 1 paints the mask in, 0 takes it out. */
  value: 0 | 1;
  description: string;
}

export function strokeTool(drawing: MaskDrawing, spec: StrokeToolSpec): PhotoTool {
  const { id, label, key, value, description } = spec;
  const { preview, brush } = drawing;
  let stroke: { objectId: string; raster: MaskRaster; last: ImagePoint } | null = null;
  const paintTo = (at: ImagePoint) => {
    if (!stroke) return;
    preview.redraw(stroke.raster.paintStroke([stroke.last, at], brush.radius, value));
    stroke.last = at;
  };
  return {
    id,
    label,
    key,
    description,
    cursor: "crosshair",
    edits: true,
    drawsOnSelected: true,
    activate: drawing.describeTarget,
    down(at, event) {
      const object = drawing.pick(event);
      if (!object) return;
      const raster = drawing.startingRaster(object);
      stroke = { objectId: object.id, raster, last: at };
      preview.show(object.id, raster);
      paintTo(at);
    },
    move(at) {
      drawing.placeCursor(at);
      paintTo(at);
    },
    up(at) {
      paintTo(at);
      const done = stroke;
      stroke = null;
      if (done) {
        const what = `${label.toLowerCase()} ${done.objectId}'s mask`;
        void drawing.save(done.objectId, done.raster, what);
      }
    },
    cancel() {
      stroke = null;
      if (!drawing.pending) preview.hide();
      drawing.placeCursor(null);
    },
    options: drawing.options(
      value ? "Drag over the photo to add to the mask." : "Drag to take pixels out of the mask.",
      true,
    ),
  };
}
