// Refine: foreground strokes over the object (Alt: background strokes over what is not it);
// after each stroke the server's GrabCut cuts the mask again from all of them, and the answer
// is saved as the object's mask.
import type { Stroke } from "@holiscene/schema";
import { errorText } from "../../api/errors";
import { refineMask } from "../../api/maskRefine";
import type { Sheet } from "../liveLayer";
import { MaskRaster, type Point } from "../maskPainting";
import type { PhotoTool } from "../photoTools";
import { intoPhoto, refineBox } from "../refineBox";
import type { MaskDrawing } from "./maskDrawing";

export const REFINE_KEY = "K";

interface RefineDraft {
  objectId: string;
  box: [number, number, number, number];
  foreground: Stroke[];
  background: Stroke[];
}

interface DrawnStroke {
  points: Point[];
  background: boolean;
}

export function refineTool(drawing: MaskDrawing): PhotoTool {
  const { live, photo, preview, brush, session } = drawing;
  let refine: RefineDraft | null = null;
  let refineStroke: DrawnStroke | null = null;
  let refineRequest = 0;
  let strokeSheet: Sheet | null = null;
  /** The mask the strokes cut last (saved, or on its way). */
  let produced: MaskRaster | null = null;

  /** Paint the refine stroke's segment from its point `from` on (all of it from 0). */
  const drawStroke = (stroke: DrawnStroke, from: number) => {
    strokeSheet ??= live.sheet(photo, { className: "refine-strokes", testid: "refine-strokes" });
    const context = strokeSheet.context;
    if (!context) return;
    context.lineCap = "round";
    context.lineJoin = "round";
    context.lineWidth = brush.size;
    context.strokeStyle = stroke.background ? "#ff4d4d" : "#2fd16b";
    context.beginPath();
    const points = stroke.points.slice(Math.max(0, from - 1));
    for (const [x, y] of points) context.lineTo(x, y);
    if (points.length === 1) context.lineTo(points[0]?.[0] ?? 0, (points[0]?.[1] ?? 0) + 0.01);
    context.stroke();
  };

  const runRefine = async () => {
    if (!refine) return;
    const box = refineBox(refine.box, refine.foreground, photo);
    const { objectId, foreground, background } = refine;
    const ticket = ++refineRequest;
    const started = performance.now();
    drawing.say("Refining the mask…");
    try {
      const answer = await refineMask(session.sceneId, { bbox: box, foreground, background });
      if (ticket !== refineRequest || refine?.objectId !== objectId) return; // overtaken
      const raster = MaskRaster.fromMask(answer.mask, photo);
      preview.show(objectId, raster);
      const total = Math.round(performance.now() - started);
      drawing.say(
        `Refined in ${total} ms (the cut ${Math.round(answer.milliseconds)} ms); saving…`,
      );
      produced = raster;
      await drawing.save(objectId, raster, `refine ${objectId}'s mask`);
    } catch (error) {
      if (ticket === refineRequest) {
        drawing.say(`The mask could not be refined: ${errorText(error)}`, true);
      }
    }
  };

  const clearRefine = () => {
    refine = null;
    refineStroke = null;
    produced = null;
    live.remove(strokeSheet);
    strokeSheet = null;
  };

  // The strokes belong to the mask they cut. When the object's mask becomes another one (Undo,
  // another tool, someone else's revision), they go: the next stroke would cut them in again.
  session.subscribe((change) => {
    if (change !== "document" || !refine || !produced || refineStroke) return;
    const object = session.object(refine.objectId);
    const now = object?.mask ? MaskRaster.fromMask(object.mask, photo) : null;
    if (!now?.samePixels(produced)) clearRefine();
  });

  return {
    id: "refine",
    label: "Refine",
    key: REFINE_KEY,
    description:
      "Refine: paint over the object (Alt: over what is not it) and the mask is cut again from the strokes",
    cursor: "crosshair",
    edits: true,
    drawsOnSelected: true,
    activate: drawing.describeTarget,
    down(at, event) {
      const object = drawing.pick(event);
      if (!object) return;
      if (refine?.objectId !== object.id) {
        clearRefine();
        const [x1, y1, x2, y2] = object.bbox;
        refine = { objectId: object.id, box: [x1, y1, x2, y2], foreground: [], background: [] };
      }
      const background = event.altKey;
      refineStroke = { points: [intoPhoto(at, photo)], background };
      drawStroke(refineStroke, 0);
    },
    move(at) {
      drawing.placeCursor(at);
      if (!refineStroke) return;
      const next = intoPhoto(at, photo);
      const last = refineStroke.points[refineStroke.points.length - 1] as Point;
      // Points closer than a quarter brush add nothing to the stroke's shape.
      if (Math.hypot(next[0] - last[0], next[1] - last[1]) < Math.max(1, brush.radius / 4)) return;
      refineStroke.points.push(next);
      drawStroke(refineStroke, refineStroke.points.length - 1);
    },
    up() {
      const done = refineStroke;
      refineStroke = null;
      if (!done || !refine) return;
      const [first, ...rest] = done.points.slice(0, 5000) as [number, number][];
      if (!first) return;
      const stroke: Stroke = { points: [first, ...rest], radius: brush.radius };
      (done.background ? refine.background : refine.foreground).push(stroke);
      if (strokeSheet) {
        strokeSheet.canvas.dataset.foreground = String(refine.foreground.length);
        strokeSheet.canvas.dataset.background = String(refine.background.length);
      }
      void runRefine();
    },
    cancel() {
      clearRefine();
      refineRequest++;
      drawing.placeCursor(null);
    },
    options: drawing.options(
      "Paint over the object; Alt+drag over what is not part of it. Each stroke cuts the mask again.",
      true,
    ),
  };
}
