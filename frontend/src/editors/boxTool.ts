// The box tool: drag on the photo where there is no object to draw a new box (then the class
// picker opens, and the object is added with that class; the server cuts its mask); press on
// an object to select it, drag it to move its box, or drag one of the selected box's 8 handles
// to resize it (set_bbox on release). Boxes stay inside the photo. What was drawn stays on the
// photo until the server's revision replaces it.

import { svgEl } from "../dom";
import { pickClass } from "../views/scene/classPicker";
import {
  type Box,
  boxFromCorners,
  dragBox,
  type Grip,
  gripAt,
  HANDLES,
  handlePoint,
  isBigEnough,
  roundBox,
} from "./boxGeometry";
import type { ImagePoint, PhotoTool, PhotoTools } from "./photoTools";

export const BOX_TOOL_KEY = "B";
const HANDLE_PX = 9; // handle size on screen
const DRAG_PX = 4; // screen pixels before a press on an object becomes a move

type Press =
  | { kind: "draw"; start: ImagePoint; box: Box }
  | {
      kind: "edit";
      id: string;
      grip: Grip;
      start: ImagePoint;
      from: Box;
      box: Box;
      moved: boolean;
    };

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

/** "chair d3" */
export const objectName = (object: { id: string; class: string }) =>
  `${object.class.replaceAll("_", " ")} ${object.id}`;

/** The rectangle of an image-pixel box on the screen (client pixels). */
export function screenRect(svg: SVGSVGElement, box: readonly number[]) {
  const matrix = svg.getScreenCTM();
  const [x1 = 0, y1 = 0, x2 = 0, y2 = 0] = box;
  const a = new DOMPoint(x1, y1).matrixTransform(matrix ?? undefined);
  const b = new DOMPoint(x2, y2).matrixTransform(matrix ?? undefined);
  return { left: a.x, top: a.y, right: b.x, bottom: b.y };
}

export function mountBoxTool(tools: PhotoTools): () => void {
  const { host } = tools;
  const { session, objects: editor, overlay, width, height } = host;
  const layer = svgEl("g", { class: "box-tool", "data-testid": "box-tool-layer" });
  overlay.append(layer);
  let press: Press | null = null;
  /** Boxes sent and not yet in a revision (drawn until the answer comes). */
  const sending = new Map<string, Box>();
  const isActive = () => tools.active.id === "box";

  const rect = (box: readonly number[], className: string, testid?: string) =>
    svgEl("rect", {
      class: className,
      "data-testid": testid,
      x: box[0],
      y: box[1],
      width: (box[2] ?? 0) - (box[0] ?? 0),
      height: (box[3] ?? 0) - (box[1] ?? 0),
      "stroke-width": host.pixelSize() * 2,
    });

  const draw = () => {
    if (!isActive()) {
      layer.replaceChildren();
      return;
    }
    const px = host.pixelSize();
    const nodes: SVGElement[] = [];
    for (const box of sending.values()) nodes.push(rect(box, "box-tool-pending"));
    const selected = session.selectedObject;
    const editing = press?.kind === "edit" ? press : null;
    const box = editing?.box ?? selected?.bbox;
    if (box && (editing || selected)) {
      nodes.push(rect(box, "box-tool-selected", "box-tool-selected"));
      const size = HANDLE_PX * px;
      for (const handle of HANDLES) {
        const [x, y] = handlePoint(box, handle);
        nodes.push(
          svgEl("rect", {
            class: "box-tool-handle",
            "data-testid": "box-handle",
            "data-handle": handle,
            x: x - size / 2,
            y: y - size / 2,
            width: size,
            height: size,
            "stroke-width": px * 1.2,
          }),
        );
      }
    }
    if (press?.kind === "draw") nodes.push(rect(press.box, "box-tool-drawing", "box-tool-drawing"));
    layer.replaceChildren(...nodes);
  };

  const addObject = async (box: Box) => {
    const key = `new-${Date.now()}`;
    sending.set(key, box);
    draw();
    const near = screenRect(host.svg, box);
    const cls = await pickClass({
      near,
      title: "Class of the new object",
      objects: session.objects,
    });
    if (!cls) {
      sending.delete(key);
      draw();
      return;
    }
    const [id = "d1"] = editor.newObjectIds(1);
    const saved = await editor.apply(
      [{ kind: "add_object", id, class: cls, bbox: roundBox(box), source: "manual" }],
      `add ${objectName({ id, class: cls })}`,
    );
    sending.delete(key);
    // Selected when saved under its id (a conflict may have given it another).
    if (saved) session.select(session.object(id) ? id : null);
    draw();
  };

  const setBox = async (id: string, box: Box, grip: Grip) => {
    const object = session.object(id);
    if (!object) return;
    sending.set(id, box);
    draw();
    const what = grip === "move" ? "move" : "resize";
    await editor.apply(
      [{ kind: "set_bbox", id, bbox: roundBox(box) }],
      `${what} the box of ${objectName(object)}`,
    );
    sending.delete(id);
    draw();
  };

  const tool: PhotoTool = {
    id: "box",
    label: "Box",
    key: BOX_TOOL_KEY,
    description:
      "Box: draw a new object's box (Shift: also over an object); drag an object or its handles to move or resize it",
    cursor: "crosshair",
    edits: true,
    down(at, event) {
      const selected = session.selectedObject;
      const grip = selected ? gripAt(selected.bbox, at, HANDLE_PX * host.pixelSize()) : null;
      // Shift: always a new box (one inside another object's, a pillow on a bed).
      const hit = event.shiftKey ? null : host.objectAt(event);
      const object = hit ? session.object(hit) : undefined;
      const edit = (id: string, bbox: readonly number[], how: Grip) => {
        const from = [...bbox] as Box;
        press = { kind: "edit", id, grip: how, start: at, from, box: from, moved: false };
      };
      // A handle of the selected box first; then the object under the pointer (a smaller one
      // inside the selected box too); then the selected box's inside; else a new box.
      if (selected && grip && grip !== "move" && !event.shiftKey)
        edit(selected.id, selected.bbox, grip);
      else if (object) {
        session.select(object.id);
        edit(object.id, object.bbox, "move");
      } else if (selected && grip === "move" && !event.shiftKey)
        edit(selected.id, selected.bbox, "move");
      else {
        session.select(null);
        press = { kind: "draw", start: at, box: boxFromCorners(at, at, width, height) };
      }
      draw();
    },
    move(at) {
      if (!press) {
        const selected = session.selectedObject;
        const grip = selected ? gripAt(selected.bbox, at, HANDLE_PX * host.pixelSize()) : null;
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
      if (done?.kind === "draw" && isBigEnough(done.box)) void addObject(done.box);
      else if (done?.kind === "edit" && done.moved && done.box.some((v, i) => v !== done.from[i]))
        void setBox(done.id, done.box, done.grip);
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
  const unsubscribe = session.subscribe((change) => {
    if (change === "document" || change === "select") draw();
  });
  return () => {
    unsubscribe();
    stopTools();
    stopView();
    removeTool();
    layer.remove();
  };
}
