// The room layout on the photo while it is edited: the fitted room's edges and a draggable
// handle on each corner the fit uses. Dragging moves the corner in the draft, which re-fits
// the room once per animation frame.
import "./layoutLayer.css";
import type { Camera } from "@holiscene/schema";
import { svgEl } from "../../dom";
import type { Point2 } from "../../geometry/camera";
import { projectBoxEdges } from "../../geometry/roomBox";
import type { LayoutDraft } from "../../state/layoutDraft";
import { type Frame, strokeWidth } from "./arrowGeometry";

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

  let dragging: number | null = null;
  const drawEdges = () => {
    const live = draft.live;
    const K = camera()?.K;
    const segments =
      live && K ? projectBoxEdges(K, live.pitchDeg, live.rollDeg, live.corners3d) : [];
    edges.setAttribute("d", segments.map(([a, b]) => `M ${fmt(a)} L ${fmt(b)}`).join(" "));
    layer.classList.toggle("is-invalid", draft.error !== null);
  };
  const drawHandles = () => {
    const radius = width * 3.2;
    handles.replaceChildren(
      ...draft.handles().map(({ index, point }) =>
        svgEl(
          "g",
          {
            class: `layout-handle${dragging === index ? " is-dragging" : ""}`,
            "data-testid": `layout-handle-${index}`,
            "data-corner": index,
            transform: `translate(${point[0].toFixed(1)} ${point[1].toFixed(1)})`,
          },
          svgEl("title", {}, `Room corner ${index} (${index < 4 ? "floor" : "ceiling"}): drag`),
          svgEl("circle", { r: radius * 1.8, class: "layout-handle-hit" }),
          svgEl("circle", { r: radius, "stroke-width": width * 0.8 }),
        ),
      ),
    );
  };
  const draw = () => {
    layer.style.display = draft.editing ? "" : "none";
    if (!draft.editing) return;
    drawEdges();
    drawHandles();
  };

  // Pointer capture keeps the drag on the handle's group while the pointer leaves it.
  handles.addEventListener("pointerdown", (event) => {
    const target = (event.target as Element).closest<SVGGElement>("[data-corner]");
    if (!target || event.button !== 0) return;
    event.preventDefault();
    event.stopPropagation();
    dragging = Number(target.dataset.corner);
    handles.setPointerCapture(event.pointerId);
    target.classList.add("is-dragging");
  });
  handles.addEventListener("pointermove", (event) => {
    if (dragging === null) return;
    const point = toImage(event);
    if (point) draft.moveCorner(dragging, point);
  });
  const endDrag = (event: PointerEvent) => {
    if (dragging === null) return;
    dragging = null;
    if (handles.hasPointerCapture(event.pointerId)) handles.releasePointerCapture(event.pointerId);
    draft.refit(); // the corner's last position, without waiting for a frame
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
