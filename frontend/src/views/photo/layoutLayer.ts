// The room layout on the photo while it is edited: the fitted room's edges and a draggable
// handle on each corner in front of the camera. A corner the fit uses (in view, or dragged)
// has a solid handle; one the fitted room places has a dashed one, and dragging it pins it.
// A corner beyond the margin around the photo has its handle on the drawing's edge with an
// arrow pointing at it (cornerHandles.ts). Dragging moves the corner in the draft by as much
// as the pointer moves, which re-fits the room once per animation frame; a drag is one step
// of the undo history.
import "./layoutLayer.css";
import type { Camera } from "@holiscene/schema";
import { svgEl } from "../../dom";
import type { Point2 } from "../../geometry/camera";
import { projectBoxEdges } from "../../geometry/roomBox";
import type { LayoutDraft } from "../../state/layoutDraft";
import { type Frame, strokeWidth } from "./arrowGeometry";
import {
  draggedCorner,
  drawingRect,
  followPointer,
  insetRect,
  offPhotoText,
  type PlacedHandle,
  placeHandles,
} from "./cornerHandles";

const fmt = (p: Point2) => `${p[0].toFixed(1)} ${p[1].toFixed(1)}`;

export function mountLayoutLayer(
  svg: SVGSVGElement,
  frame: Frame,
  draft: LayoutDraft,
  camera: () => Camera | null | undefined,
): () => void {
  const width = strokeWidth(frame);
  const edges = svgEl("path", {
    class: "layout-edges",
    "data-testid": "layout-edges",
    "stroke-width": width,
  });
  const handles = svgEl("g", { class: "layout-handles" });
  const layer = svgEl(
    "g",
    { class: "layout-layer", "data-testid": "layout-layer" },
    edges,
    handles,
  );
  svg.append(layer);

  const toImage = (event: PointerEvent): Point2 | null => {
    const matrix = svg.getScreenCTM();
    if (!matrix) return null;
    const p = new DOMPoint(event.clientX, event.clientY).matrixTransform(matrix.inverse());
    return [p.x, p.y];
  };

  /** The corner being dragged: where it and its handle were, and where the pointer was. */
  let drag: { index: number; corner: Point2; grabbedAt: Point2; handleAt: Point2 } | null = null;
  /** The handles as last drawn, by corner index. */
  let drawn = new Map<number, PlacedHandle>();
  const radius = width * 3.2;
  // A handle on the edge is larger: it stands for a corner one cannot see.
  const clampedRadius = radius * 1.4;
  // The drawing (the photo and its margin) and where clamped handles sit, whole, inside it.
  const area = drawingRect(frame);
  const border = insetRect(area, clampedRadius * 1.15);

  const drawEdges = () => {
    const live = draft.live;
    const K = camera()?.K;
    const segments =
      live && K ? projectBoxEdges(K, live.pitchDeg, live.rollDeg, live.corners3d) : [];
    edges.setAttribute("d", segments.map(([a, b]) => `M ${fmt(a)} L ${fmt(b)}`).join(" "));
    layer.classList.toggle("is-invalid", draft.error !== null);
  };
  const handleTitle = (h: PlacedHandle) => {
    const name = `Room corner ${h.index} (${h.index < 4 ? "floor" : "ceiling"})`;
    const where = h.clamped ? `, ${offPhotoText(h.corner, frame.width, frame.height)}` : "";
    const how = h.pinned ? "" : "; placed by the fitted room until you drag it";
    const action = h.clamped ? "drag to move it by as much as you drag" : "drag";
    return `${name}${where}${how}: ${action}`;
  };
  const handleNode = (h: PlacedHandle) => {
    const classes = [
      "layout-handle",
      h.pinned ? "" : "is-free",
      h.clamped ? "is-clamped" : "",
      drag?.index === h.index ? "is-dragging" : "",
    ];
    const r = h.clamped ? clampedRadius : radius;
    const parts: SVGElement[] = [
      svgEl("title", {}, handleTitle(h)),
      svgEl("circle", { r: radius * 1.8, class: "layout-handle-hit" }),
      svgEl("circle", { r, "stroke-width": width * 0.8 }),
    ];
    if (h.direction) {
      // An arrowhead inside the handle, pointing at the corner off the photo.
      const [dx, dy] = h.direction;
      const tip: Point2 = [dx * r * 0.8, dy * r * 0.8];
      const base: Point2 = [-dx * r * 0.45, -dy * r * 0.45];
      const side: Point2 = [-dy * r * 0.6, dx * r * 0.6];
      const d =
        `M ${fmt(tip)} L ${fmt([base[0] + side[0], base[1] + side[1]])} ` +
        `L ${fmt([base[0] - side[0], base[1] - side[1]])} Z`;
      parts.push(svgEl("path", { class: "layout-handle-arrow", d }));
    }
    return svgEl(
      "g",
      {
        class: classes.filter(Boolean).join(" "),
        "data-testid": `layout-handle-${h.index}`,
        "data-corner": h.index,
        "data-pinned": String(h.pinned),
        "data-clamped": String(h.clamped),
        "data-x": h.corner[0].toFixed(2),
        "data-y": h.corner[1].toFixed(2),
        transform: `translate(${h.at[0].toFixed(1)} ${h.at[1].toFixed(1)})`,
      },
      ...parts,
    );
  };
  const drawHandles = () => {
    const placed = placeHandles(draft.handles(), area, border, clampedRadius * 2.2).map((h) =>
      drag?.index === h.index ? followPointer(h, drag.handleAt, drag.corner, border) : h,
    );
    drawn = new Map(placed.map((h) => [h.index, h]));
    handles.replaceChildren(...placed.map(handleNode));
  };
  const draw = () => {
    layer.style.display = draft.editing ? "" : "none";
    if (!draft.editing) return;
    drawEdges();
    drawHandles();
  };

  // Pointer capture keeps the drag on the handles' group while the pointer leaves a handle.
  handles.addEventListener("pointerdown", (event) => {
    const target = (event.target as Element).closest<SVGGElement>("[data-corner]");
    if (!target || event.button !== 0 || drag !== null) return;
    const grabbedAt = toImage(event);
    if (!grabbedAt) return;
    event.preventDefault();
    event.stopPropagation();
    const index = Number(target.dataset.corner);
    const corner = draft.beginDrag(index);
    if (!corner) return;
    drag = { index, corner, grabbedAt, handleAt: drawn.get(index)?.at ?? corner };
    handles.setPointerCapture(event.pointerId);
    target.classList.add("is-dragging");
  });
  handles.addEventListener("pointermove", (event) => {
    if (drag === null) return;
    const point = toImage(event);
    if (point) draft.moveCorner(drag.index, draggedCorner(drag.corner, drag.grabbedAt, point));
  });
  const endDrag = (event: PointerEvent) => {
    if (drag === null) return;
    drag = null;
    if (handles.hasPointerCapture(event.pointerId)) handles.releasePointerCapture(event.pointerId);
    draft.endDrag(); // the corner's last position, without waiting for a frame; one undo step
  };
  handles.addEventListener("pointerup", endDrag);
  handles.addEventListener("pointercancel", endDrag);
  // A click on a handle is not a click on the object under it.
  handles.addEventListener("click", (event) => event.stopPropagation());

  draw();
  const unsubscribe = draft.subscribe(draw);
  return () => {
    unsubscribe();
    layer.remove();
  };
}
