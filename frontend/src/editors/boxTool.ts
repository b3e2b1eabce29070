// The box tool: drag on the photo to draw a new box, also over an object (then the class picker
// opens, and the object is added with that class; the server cuts its mask); click an object to
// select it, then drag inside its box to move it or drag one of its 8 handles to resize it
// (set_bbox on release). Boxes stay inside the photo. What was drawn stays on the
// photo until the server's revision replaces it.

import { svgEl } from "../dom";
import { BoxEdits } from "./boxes/boxEdits";
import { drawBoxLayer, handleReach } from "./boxes/boxLayer";
import { type Press, startPress } from "./boxes/boxPress";
import { boxFromCorners, dragBox, type Grip, gripAt, isBigEnough } from "./boxGeometry";
import { type PhotoTool, type PhotoTools, toolHint } from "./photoTools";

export const BOX_TOOL_KEY = "B";
const DRAG_PX = 4; // screen pixels before a press on an object becomes a move

const CURSORS: Record<Grip, string> = {
  nw: "nwse-resize",
  se: "nwse-resize",
  ne: "nesw-resize",
  sw: "nesw-resize",
  n: "ns-resize",
  s: "ns-resize",
  e: "ew-resize",
  w: "ew-resize",
  move: "move",
};

export function mountBoxTool(tools: PhotoTools): () => void {
  const { host } = tools;
  const { session, overlay, width, height } = host;
  const layer = svgEl("g", { class: "box-tool", "data-testid": "box-tool-layer" });
  overlay.append(layer);
  let press: Press | null = null;
  const edits = new BoxEdits(host, () => draw());
  const isActive = () => tools.active.id === "box";

  const draw = () => {
    if (!isActive()) {
      layer.replaceChildren();
      return;
    }
    drawBoxLayer(layer, {
      sending: edits.sending.values(),
      selected: session.selectedObject,
      editing: press?.kind === "edit" ? press.box : null,
      drawing: press?.kind === "draw" ? press.box : null,
      pixelSize: host.pixelSize(),
    });
  };

  const tool: PhotoTool = {
    id: "box",
    label: "Box",
    key: BOX_TOOL_KEY,
    description:
      "Box: drag to draw a new object's box (Shift: also inside the selected one); click an object to select it, then drag its inside or handles to move or resize it",
    cursor: "crosshair",
    edits: true,
    options: () =>
      toolHint(
        "Drag to draw a box (Shift: inside the selected one); drag the selected box or a handle to move or resize it.",
      ),
    down(at, event) {
      // Shift: always a new box (one inside the selected object's, a pillow on a bed).
      const hit = event.shiftKey ? null : host.objectAt(event);
      const start = startPress(at, {
        selected: session.selectedObject,
        under: hit ? session.object(hit) : undefined,
        shift: event.shiftKey,
        pixelSize: host.pixelSize(),
        width,
        height,
      });
      press = start.press;
      if (start.select !== undefined) session.select(start.select);
      draw();
    },
    move(at) {
      if (!press) {
        const selected = session.selectedObject;
        const grip = selected
          ? gripAt(selected.bbox, at, handleReach(selected.bbox, host.pixelSize()))
          : null;
        host.svg.style.cursor = grip ? CURSORS[grip] : "crosshair";
        return;
      }
      if (press.kind === "draw") press.box = boxFromCorners(press.start, at, width, height);
      else {
        const [dx, dy] = [at[0] - press.start[0], at[1] - press.start[1]];
        press.moved ||= Math.hypot(dx, dy) >= DRAG_PX * host.pixelSize();
        if (press.moved) press.box = dragBox(press.from, press.grip, dx, dy, width, height);
      }
      draw();
    },
    up() {
      const done = press;
      press = null;
      if (done?.kind === "draw") {
        if (isBigEnough(done.box)) void edits.addObject(done.box);
        else if (done.pick !== null) session.select(done.pick); // a click on an object
      } else if (done?.kind === "edit" && done.moved && done.box.some((v, i) => v !== done.from[i]))
        void edits.setBox(done.id, done.box, done.grip);
      draw();
    },
    cancel() {
      press = null;
      draw();
    },
    activate: draw,
  };
  const removeTool = tools.add(tool);
  const stopTools = tools.onChange(draw);
  const stopView = host.onView(draw);
  // A new revision or selection is drawn in the next frame, not at once: the layer asks for
  // the photo's scale on the screen, which right after the masks changed forces a layout in
  // the middle of the redraw (the frame lays the page out anyway).
  let frame = 0;
  const drawSoon = () => {
    frame ||= requestAnimationFrame(() => {
      frame = 0;
      draw();
    });
  };
  const unsubscribe = session.subscribe((change) => {
    if (change === "document" || change === "select") drawSoon();
  });
  return () => {
    edits.leave();
    cancelAnimationFrame(frame);
    unsubscribe();
    stopTools();
    stopView();
    removeTool();
    layer.remove();
  };
}
