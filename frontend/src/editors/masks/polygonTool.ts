// Polygon: click points around a part of the object; Enter or a click on the first point
// closes it and adds it to the mask (Shift: takes it out). Backspace drops the last point. A
// mask that is still its box (the pipeline could not cut one) is replaced by the polygon:
// added to the box it would change nothing.
import type { Sheet } from "../liveLayer";
import { MaskRaster } from "../maskPainting";
import type { ImagePoint, PhotoTool } from "../photoTools";
import type { MaskDrawing } from "./maskDrawing";

export const POLYGON_KEY = "G";
/** How near (in screen pixels) a click must be to the first point to close the polygon. */
const CLOSE_DISTANCE = 9;

interface Draft {
  objectId: string;
  points: ImagePoint[];
  subtract: boolean;
}

export interface PolygonTool {
  tool: PhotoTool;
  /** A polygon is being drawn. */
  drafting(): boolean;
  /** How many points the polygon being drawn has (0: none is). */
  points(): number;
  /** Close the polygon being drawn (Enter). */
  close(): void;
  /** Take back the last point (Backspace); the polygon goes with its last point. */
  dropPoint(): void;
  /** Draw it again (the photo was zoomed, panned or resized). */
  redraw(): void;
}

/** A mask this full of its box is the box itself (the pipeline's fallback, or none at all). */
const BOX_FILL = 0.97;

/** Whether the mask covers (nearly) all of its object's box. */
function fillsItsBox(raster: MaskRaster, bbox: readonly number[]): boolean {
  const [x1 = 0, y1 = 0, x2 = 0, y2 = 0] = bbox;
  const area = Math.round(x2 - x1) * Math.round(y2 - y1);
  return area > 0 && raster.count() >= BOX_FILL * area;
}

export function polygonTool(drawing: MaskDrawing): PolygonTool {
  const { host, live, photo, preview, session } = drawing;
  let polygon: Draft | null = null;
  let pointer: ImagePoint | null = null;
  let sheet: Sheet | null = null;

  const draw = () => {
    if (!polygon) {
      live.remove(sheet);
      sheet = null;
      return;
    }
    sheet ??= live.sheet(photo, { className: "polygon-draft", testid: "polygon-draft" });
    const { canvas, context } = sheet;
    canvas.dataset.points = String(polygon.points.length);
    canvas.classList.toggle("is-subtract", polygon.subtract);
    if (!context) return;
    const unit = host.pixelSize();
    const path = [...polygon.points, ...(pointer ? [pointer] : [])];
    const [first] = polygon.points as [ImagePoint];
    context.clearRect(0, 0, canvas.width, canvas.height);
    context.beginPath();
    for (const [x, y] of path) context.lineTo(x, y);
    context.closePath();
    context.fillStyle = polygon.subtract ? "rgba(179, 38, 30, 0.3)" : "rgba(255, 255, 255, 0.25)";
    context.fill();
    context.lineWidth = unit * 2;
    context.lineJoin = "round";
    context.strokeStyle = polygon.subtract ? "#ff8a80" : "#ffffff";
    context.setLineDash(polygon.subtract ? [unit * 6, unit * 4] : []);
    context.stroke();
    // The first point: a click on it closes the polygon.
    context.setLineDash([]);
    context.beginPath();
    context.arc(first[0], first[1], unit * (CLOSE_DISTANCE - 2), 0, 2 * Math.PI);
    context.fillStyle = "rgba(255, 255, 255, 0.7)";
    context.fill();
    context.lineWidth = unit * 1.5;
    context.strokeStyle = "#000000";
    context.stroke();
  };

  const close = (subtract: boolean) => {
    const draft = polygon;
    polygon = null;
    draw();
    if (!draft || draft.points.length < 3) return;
    const object = session.object(draft.objectId);
    if (!object) return;
    const start = drawing.startingRaster(object);
    const replace = !subtract && fillsItsBox(start, object.bbox);
    const raster = replace ? new MaskRaster(drawing.photo) : start;
    raster.fillPolygon(draft.points, subtract ? 0 : 1);
    preview.show(object.id, raster);
    const what = replace
      ? `replace ${object.id}'s box-shaped mask with a polygon`
      : `${subtract ? "cut a polygon from" : "add a polygon to"} ${object.id}'s mask`;
    void drawing.save(object.id, raster, what);
  };

  const tool: PhotoTool = {
    id: "polygon",
    label: "Polygon",
    key: POLYGON_KEY,
    description: "Polygon: click points around a part to add it to the mask (Shift: take it out)",
    cursor: "crosshair",
    edits: true,
    drawsOnSelected: true,
    activate: drawing.describeTarget,
    drafting: () => polygon !== null,
    down(at, event) {
      if (!polygon) {
        const object = drawing.pick(event);
        if (!object) return;
        polygon = { objectId: object.id, points: [at], subtract: event.shiftKey };
      } else {
        const first = polygon.points[0] as ImagePoint;
        const near =
          Math.hypot(at[0] - first[0], at[1] - first[1]) <= CLOSE_DISTANCE * host.pixelSize();
        if (near && polygon.points.length >= 3) {
          close(polygon.subtract || event.shiftKey);
          return;
        }
        polygon.points.push(at);
      }
      pointer = at;
      draw();
    },
    move(at) {
      pointer = at;
      if (polygon) draw();
    },
    cancel() {
      polygon = null;
      pointer = null;
      draw();
    },
    options: drawing.options(
      "Click points; Enter or the first point closes; Shift: cut out; Backspace: drop a point.",
      false,
    ),
  };

  return {
    tool,
    drafting: () => polygon !== null,
    points: () => polygon?.points.length ?? 0,
    close: () => close(polygon?.subtract ?? false),
    dropPoint() {
      polygon?.points.pop();
      if (polygon?.points.length === 0) polygon = null;
      draw();
    },
    redraw: draw,
  };
}
