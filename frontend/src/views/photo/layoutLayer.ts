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
  type PlacedHandle,
  placeHandles,
} from "./cornerHandles";
import { fmt, type HandleStyle, handleNode } from "./layoutHandle";
import { toImage } from "./photoSvg";

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
  // From a corner put where the room cannot reach to where the room puts it (the bar says so).
  const miss = svgEl("path", {
    class: "layout-miss",
    "data-testid": "layout-miss",
    "stroke-width": width,
    "stroke-dasharray": `${width * 3} ${width * 2}`,
  });
  // Said on the photo, at the line's end, not in the bar above it: a longer bar line would
  // move the photo under the pointer, and the autosave's message would replace it.
  const missLabel = svgEl("text", {
    class: "layout-miss-label",
    "data-testid": "layout-miss-label",
    "font-size": width * 5,
    "stroke-width": width * 1.2,
  });
  const layer = svgEl(
    "g",
    { class: "layout-layer", "data-testid": "layout-layer" },
    edges,
    miss,
    missLabel,
    handles,
  );
  svg.append(layer);

  const toPhoto = (event: PointerEvent): Point2 | null => toImage(svg, event);

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
    const missed = draft.miss();
    miss.setAttribute("d", missed ? `M ${fmt(missed.corner)} L ${fmt(missed.fitted)}` : "");
    miss.dataset.corner = missed ? String(missed.index) : "";
    missLabel.textContent = missed ? "corner goes here when saved" : "";
    if (missed) {
      missLabel.append(
        svgEl(
          "title",
          {},
          `A box room cannot reach the ${missed.name} where it was put: the nearest it can ` +
            `is ${Math.round(missed.px)} px away, at the end of the dashed line`,
        ),
      );
      // Beside the line's end, on the side away from the handle, inside the drawing.
      const [x, y] = missed.fitted;
      const below = missed.corner[1] < y;
      const left = x > (area.left + area.right) / 2;
      missLabel.setAttribute("x", (x + (left ? -1 : 1) * width * 3).toFixed(1));
      missLabel.setAttribute("y", (y + (below ? 1 : -1) * width * 6).toFixed(1));
      missLabel.setAttribute("text-anchor", left ? "end" : "start");
    }
    layer.classList.toggle("is-invalid", draft.error !== null);
  };
  const style: HandleStyle = { frame, strokeWidth: width, radius, clampedRadius };
  const drawHandles = () => {
    const placed = placeHandles(draft.handles(), area, border, clampedRadius * 2.2).map((h) =>
      drag?.index === h.index ? followPointer(h, drag.handleAt, drag.corner, border) : h,
    );
    drawn = new Map(placed.map((h) => [h.index, h]));
    handles.replaceChildren(...placed.map((h) => handleNode(h, style, drag?.index === h.index)));
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
    const grabbedAt = toPhoto(event);
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
    const point = toPhoto(event);
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
