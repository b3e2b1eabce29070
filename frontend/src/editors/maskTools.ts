// The mask tools on the photo: Brush (adds to the selected object's mask), Eraser (takes
// away), Polygon (click points; Enter or a click on the first point closes it; Shift
// subtracts) and Refine (foreground strokes, Alt for background, cut by the server's GrabCut).
// What a tool draws is shown at once in place of the stored mask (maskPreview.ts); when the
// pointer is released or the polygon closes, the new mask goes to the server as one set_mask
// edit (objectEditor.apply: one revision, undoable). With no object selected, a press on an
// object selects it, and a press elsewhere says what to do.
import type { SceneObject, Stroke } from "@holiscene/schema";
import { refineMask } from "../api/maskRefine";
import { el } from "../dom";
import { registerShortcut } from "../shortcuts";
import { LiveLayer, type Sheet } from "./liveLayer";
import { MaskRaster, type PixelRect, type Point } from "./maskPainting";
import { MaskPreview } from "./maskPreview";
import type { ImagePoint, PhotoTool, PhotoTools } from "./photoTools";
import { intoPhoto, refineBox } from "./refineBox";
import "./maskTools.css";

export const BRUSH_KEY = "P";
export const ERASER_KEY = "Shift+P";
export const POLYGON_KEY = "G";
export const REFINE_KEY = "K";
export const SMALLER_KEY = "[";
export const LARGER_KEY = "]";
const SCOPE = "Mask tools";

/** Brush sizes: the diameter in photo pixels. */
const MIN_SIZE = 2;
const MAX_SIZE = 160;
const DEFAULT_SIZE = 16;
const SIZE_STEP = 1.25;
/** How near (in screen pixels) a click must be to the first point to close the polygon. */
const CLOSE_DISTANCE = 9;

const NEED_OBJECT = "Select an object first (click it on the photo or in the list).";

const errorText = (error: unknown) => (error instanceof Error ? error.message : String(error));

/** The brush size shared by Brush, Eraser and Refine: a slider, and [ ] to step it. */
class BrushSize {
  size = DEFAULT_SIZE;
  readonly input = el("input", {
    testid: "brush-size",
    attrs: {
      type: "range",
      min: MIN_SIZE,
      max: MAX_SIZE,
      step: 1,
      value: DEFAULT_SIZE,
      "aria-label": "Brush size in photo pixels",
      title: `Brush size in photo pixels (${SMALLER_KEY} smaller, ${LARGER_KEY} larger)`,
    },
    on: { input: () => this.set(Number(this.input.value)) },
  });
  private readonly value = el("span", {
    className: "brush-size-value",
    testid: "brush-size-value",
  });
  readonly element = el("label", { className: "brush-size" }, "Size", this.input, this.value);
  private readonly listeners = new Set<() => void>();

  constructor() {
    this.set(DEFAULT_SIZE);
  }

  get radius(): number {
    return this.size / 2;
  }

  set(size: number): void {
    this.size = Math.round(Math.min(MAX_SIZE, Math.max(MIN_SIZE, size)));
    this.input.value = String(this.size);
    this.value.textContent = `${this.size} px`;
    for (const listener of this.listeners) listener();
  }

  step(up: boolean): void {
    const next = up ? this.size * SIZE_STEP : this.size / SIZE_STEP;
    // At small sizes a factor would round back to the same size.
    this.set(up ? Math.max(next, this.size + 1) : Math.min(next, this.size - 1));
  }

  onChange(listener: () => void): void {
    this.listeners.add(listener);
  }
}

/** Mount the four tools on the photo's toolbar; returns the function that removes them. */
export function mountMaskTools(tools: PhotoTools): () => void {
  const { host } = tools;
  const { session } = host;
  const photo: PixelRect = { left: 0, top: 0, right: host.width, bottom: host.height };
  const live = new LiveLayer(host.svg);
  const preview = new MaskPreview(host.svg, live);
  const brush = new BrushSize();
  const status = el("span", {
    className: "mask-tool-status",
    testid: "mask-tool-status",
    attrs: { role: "status" },
  });
  const say = (text: string, error = false) => {
    status.textContent = text;
    status.title = text; // the line may cut it short
    status.classList.toggle("is-error", error);
  };

  /** The object to draw on; with none selected, a press on an object selects it instead. */
  const pick = (event: PointerEvent): SceneObject | null => {
    const object = session.selectedObject;
    if (object) return object;
    const under = host.objectAt(event);
    if (under) {
      session.select(under);
      say(`Selected ${under}: now draw on its mask.`);
    } else say(NEED_OBJECT, true);
    return null;
  };
  const describeTarget = () => {
    const object = session.selectedObject;
    say(object ? `Mask of ${object.class} ${object.id}` : NEED_OBJECT, !object);
  };

  // The mask drawn last but maybe not yet adopted from the server: the next stroke on the same
  // object starts from it, so quick strokes do not undo each other.
  let pending: { objectId: string; raster: MaskRaster } | null = null;

  /** What the object's mask is now, as a raster over the photo (its box when it has none). */
  const startingRaster = (object: SceneObject): MaskRaster => {
    if (pending?.objectId === object.id) return pending.raster.copy();
    if (object.mask) return MaskRaster.fromMask(object.mask, photo);
    const raster = new MaskRaster(photo);
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
  };

  /** Send the drawn mask as one set_mask edit; the preview stays until the answer is in. */
  const save = async (objectId: string, raster: MaskRaster, label: string) => {
    const mask = raster.toMask("manual");
    if (!mask) {
      preview.hide();
      pending = null;
      say("That would leave no mask at all: to take the object away, remove it instead.", true);
      return;
    }
    pending = { objectId, raster };
    const saved = await host.objects.apply([{ kind: "set_mask", id: objectId, mask }], label);
    if (pending?.raster === raster) pending = null;
    if (!saved) say(`${label}: not saved (see the message above the photo).`, true);
    // A newer drawing, begun on this one, may be on screen already: it stays.
    if (!preview.showing(raster)) return;
    preview.hide();
    if (saved) describeTarget();
  };

  let cursorAt: ImagePoint | null = null;
  const placeCursor = (at: ImagePoint | null) => {
    cursorAt = at;
    live.showCursor(at, brush.radius);
  };

  const options = (hint: string, withSize: boolean) => () =>
    el(
      "span",
      { className: "mask-tool-options" },
      withSize ? brush.element : null,
      el("span", { className: "mask-tool-hint", text: hint }),
      status,
    );

  /** Brush and Eraser: paint the selected object's mask in (1) or out (0). */
  const strokeTool = (
    id: string,
    label: string,
    key: string,
    value: 0 | 1,
    description: string,
  ): PhotoTool => {
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
      activate: describeTarget,
      down(at, event) {
        const object = pick(event);
        if (!object) return;
        const raster = startingRaster(object);
        stroke = { objectId: object.id, raster, last: at };
        preview.show(object.id, raster);
        paintTo(at);
      },
      move(at) {
        placeCursor(at);
        paintTo(at);
      },
      up(at) {
        paintTo(at);
        const done = stroke;
        stroke = null;
        if (done)
          void save(done.objectId, done.raster, `${label.toLowerCase()} ${done.objectId}'s mask`);
      },
      cancel() {
        stroke = null;
        if (!pending) preview.hide();
        placeCursor(null);
      },
      options: options(
        value ? "Drag over the photo to add to the mask." : "Drag to take pixels out of the mask.",
        true,
      ),
    };
  };

  // --- Polygon ---------------------------------------------------------------------------
  let polygon: { objectId: string; points: ImagePoint[]; subtract: boolean } | null = null;
  let pointer: ImagePoint | null = null;
  let polygonSheet: Sheet | null = null;
  const drawPolygon = () => {
    if (!polygon) {
      live.remove(polygonSheet);
      polygonSheet = null;
      return;
    }
    polygonSheet ??= live.sheet(photo, { className: "polygon-draft", testid: "polygon-draft" });
    const { canvas, context } = polygonSheet;
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
  const closePolygon = (subtract: boolean) => {
    const draft = polygon;
    polygon = null;
    drawPolygon();
    if (!draft || draft.points.length < 3) return;
    const object = session.object(draft.objectId);
    if (!object) return;
    const raster = startingRaster(object);
    raster.fillPolygon(draft.points, subtract ? 0 : 1);
    preview.show(object.id, raster);
    void save(
      object.id,
      raster,
      `${subtract ? "cut a polygon from" : "add a polygon to"} ${object.id}'s mask`,
    );
  };
  const polygonTool: PhotoTool = {
    id: "polygon",
    label: "Polygon",
    key: POLYGON_KEY,
    description: "Polygon: click points around a part to add it to the mask (Shift: take it out)",
    cursor: "crosshair",
    edits: true,
    activate: describeTarget,
    drafting: () => polygon !== null,
    down(at, event) {
      if (!polygon) {
        const object = pick(event);
        if (!object) return;
        polygon = { objectId: object.id, points: [at], subtract: event.shiftKey };
      } else {
        const first = polygon.points[0] as ImagePoint;
        const near =
          Math.hypot(at[0] - first[0], at[1] - first[1]) <= CLOSE_DISTANCE * host.pixelSize();
        if (near && polygon.points.length >= 3) {
          closePolygon(polygon.subtract || event.shiftKey);
          return;
        }
        polygon.points.push(at);
      }
      pointer = at;
      drawPolygon();
    },
    move(at) {
      pointer = at;
      if (polygon) drawPolygon();
    },
    cancel() {
      polygon = null;
      pointer = null;
      drawPolygon();
    },
    options: options(
      "Click points; Enter or the first point closes; Shift: cut out; Backspace: drop a point.",
      false,
    ),
  };

  // --- Refine ----------------------------------------------------------------------------
  let refine: {
    objectId: string;
    box: [number, number, number, number];
    foreground: Stroke[];
    background: Stroke[];
  } | null = null;
  let refineStroke: { points: Point[]; background: boolean } | null = null;
  let refineRequest = 0;
  let strokeSheet: Sheet | null = null;
  /** Paint the refine stroke's segment from its point `from` on (all of it from 0). */
  const drawStroke = (stroke: { points: Point[]; background: boolean }, from: number) => {
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
    say("Refining the mask…");
    try {
      const answer = await refineMask(session.sceneId, { bbox: box, foreground, background });
      if (ticket !== refineRequest || refine?.objectId !== objectId) return; // overtaken
      const raster = MaskRaster.fromMask(answer.mask, photo);
      preview.show(objectId, raster);
      const total = Math.round(performance.now() - started);
      say(`Refined in ${total} ms (the cut ${Math.round(answer.milliseconds)} ms); saving…`);
      await save(objectId, raster, `refine ${objectId}'s mask`);
    } catch (error) {
      if (ticket === refineRequest) say(`The mask could not be refined: ${errorText(error)}`, true);
    }
  };
  const clearRefine = () => {
    refine = null;
    refineStroke = null;
    live.remove(strokeSheet);
    strokeSheet = null;
  };
  const refineTool: PhotoTool = {
    id: "refine",
    label: "Refine",
    key: REFINE_KEY,
    description:
      "Refine: paint over the object (Alt: over what is not it) and the mask is cut again from the strokes",
    cursor: "crosshair",
    edits: true,
    activate: describeTarget,
    down(at, event) {
      const object = pick(event);
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
      placeCursor(at);
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
      placeCursor(null);
    },
    options: options(
      "Paint over the object; Alt+drag over what is not part of it. Each stroke cuts the mask again.",
      true,
    ),
  };

  const brushTool = strokeTool(
    "brush",
    "Brush",
    BRUSH_KEY,
    1,
    "Brush: paint the selected object's mask",
  );
  const eraserTool = strokeTool(
    "eraser",
    "Eraser",
    ERASER_KEY,
    0,
    "Eraser: take pixels out of the selected object's mask",
  );
  const maskTools: PhotoTool[] = [brushTool, eraserTool, polygonTool, refineTool];
  const removers = maskTools.map((tool) => tools.add(tool));

  const sized = () =>
    [brushTool, eraserTool, refineTool].includes(tools.active) && session.editable;
  const drafting = () => tools.active === polygonTool && polygon !== null;
  removers.push(
    registerShortcut({
      keys: SMALLER_KEY,
      description: "Smaller brush (Brush, Eraser, Refine)",
      scope: SCOPE,
      run: () => brush.step(false),
      enabled: sized,
    }),
    registerShortcut({
      keys: LARGER_KEY,
      description: "Larger brush (Brush, Eraser, Refine)",
      scope: SCOPE,
      run: () => brush.step(true),
      enabled: sized,
    }),
    registerShortcut({
      keys: "Enter",
      description: "Close the polygon being drawn",
      scope: SCOPE,
      run: () => closePolygon(polygon?.subtract ?? false),
      enabled: () => drafting() && (polygon?.points.length ?? 0) >= 3,
    }),
    registerShortcut({
      keys: "Backspace",
      description: "Take back the polygon's last point (while drawing one)",
      scope: SCOPE,
      run: () => {
        polygon?.points.pop();
        if (polygon?.points.length === 0) polygon = null;
        drawPolygon();
      },
      enabled: drafting,
    }),
  );
  brush.onChange(() => {
    placeCursor(cursorAt);
  });
  const stopSelect = session.subscribe((change) => {
    // A revision adopted while a newer drawing is shown must not show through it.
    if (change === "document") preview.keepStoredHidden();
    if (change === "select" && maskTools.includes(tools.active)) describeTarget();
  });
  const hideCursor = () => placeCursor(null);
  const replace = () => {
    live.place();
    drawPolygon();
  };
  const stopView = host.onView(replace);
  // The photo's size follows its panel (window, side panels), not only the window.
  const resized = new ResizeObserver(replace);
  resized.observe(host.svg);
  host.svg.addEventListener("pointerleave", hideCursor);

  return () => {
    stopSelect();
    host.svg.removeEventListener("pointerleave", hideCursor);
    resized.disconnect();
    for (const remove of removers) remove();
    preview.hide();
    stopView();
    live.dispose();
  };
}
