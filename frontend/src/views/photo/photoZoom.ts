// Zoom and pan of the photo by its SVG viewBox (hit-testing goes through getScreenCTM, so it
// keeps working): the wheel zooms about the pointer, a drag with the middle button or with
// Space held pans, + and - zoom about the middle, 0 fits the whole photo again. The view never
// leaves the photo's frame and is never smaller than it (arrows and labels, drawn in image
// pixels, only get larger); tools size their handles by the screen (host.pixelSize).
import { button, el } from "../../dom";
import { photoPan } from "./photoPan";
import { toImage } from "./photoSvg";
import { photoZoomKeys } from "./photoZoomKeys";

export interface ViewBox {
  x: number;
  y: number;
  width: number;
  height: number;
}

export const MAX_ZOOM = 16;
const WHEEL_RATE = 0.0015; // zoom factor per wheel delta pixel (exp)
const KEY_STEP = 1.25;

/**
 * The view of `frame` at `zoom` (1: all of it) that keeps image point `at` where it was in
 * `view`, moved inside the frame.
 */
export function zoomedView(
  frame: ViewBox,
  view: ViewBox,
  zoom: number,
  at: [number, number],
): ViewBox {
  const scale = Math.min(MAX_ZOOM, Math.max(1, zoom));
  const width = frame.width / scale;
  const height = frame.height / scale;
  const x = at[0] - ((at[0] - view.x) * width) / view.width;
  const y = at[1] - ((at[1] - view.y) * height) / view.height;
  return clampView(frame, { x, y, width, height });
}

/** `view` moved (not resized) to lie inside `frame`. */
export function clampView(frame: ViewBox, view: ViewBox): ViewBox {
  const clamp = (v: number, low: number, high: number) => Math.min(high, Math.max(low, v));
  return {
    ...view,
    x: clamp(view.x, frame.x, frame.x + frame.width - view.width),
    y: clamp(view.y, frame.y, frame.y + frame.height - view.height),
  };
}

export interface PhotoZoom {
  /** 1: the whole photo. */
  readonly zoom: number;
  /** The zoom in percent and a Fit button, for a toolbar. */
  readonly controls: HTMLElement;
  fit(): void;
  /** Told after every zoom or pan. */
  onChange(listener: () => void): () => void;
  dispose(): void;
}

/**
 * Zoom and pan `svg`, whose viewBox is `frame` when it fits. Mount it before other pointer
 * handlers of the photo: a pan's press goes to nobody else.
 */
export function mountPhotoZoom(svg: SVGSVGElement, frame: ViewBox): PhotoZoom {
  let view = { ...frame };
  const listeners = new Set<() => void>();

  const percent = el("span", { className: "photo-zoom-level", testid: "photo-zoom-level" });
  const fitButton = button("Fit", {
    testid: "photo-zoom-fit",
    title: "Show the whole photo (0); the wheel zooms, Space+drag pans",
    onClick: () => showWhole(),
  });
  const controls = el(
    "span",
    { className: "photo-zoom", attrs: { hidden: true } },
    percent,
    fitButton,
  );

  const apply = (next: ViewBox) => {
    view = next;
    svg.setAttribute("viewBox", `${view.x} ${view.y} ${view.width} ${view.height}`);
    const zoom = frame.width / view.width;
    svg.dataset.zoom = zoom.toFixed(3);
    // Shown only while zoomed: the way back is then in sight.
    percent.textContent = `${Math.round(zoom * 100)}%`;
    controls.hidden = zoom < 1.001;
    for (const listener of listeners) listener();
  };
  const showWhole = () => apply({ ...frame });
  const zoomAt = (factor: number, at: [number, number]) =>
    apply(zoomedView(frame, view, (frame.width / view.width) * factor, at));
  const middle = (): [number, number] => [view.x + view.width / 2, view.y + view.height / 2];
  const onWheel = (event: WheelEvent) => {
    const at = toImage(svg, event);
    if (!at) return;
    event.preventDefault(); // the page does not scroll while the photo zooms
    const lines = event.deltaMode === 1 ? 16 : 1;
    zoomAt(Math.exp(-event.deltaY * lines * WHEEL_RATE), at);
  };
  // One signal takes every listener off again in dispose().
  const listening = new AbortController();
  const { signal } = listening;
  svg.addEventListener("wheel", onWheel, { passive: false, signal });
  // Panning moves the view by as much as the pointer moved, inside the frame.
  const pan = photoPan(
    svg,
    (dx, dy) => apply(clampView(frame, { ...view, x: view.x - dx, y: view.y - dy })),
    signal,
  );

  const removeKeys = photoZoomKeys({
    zoomIn: () => zoomAt(KEY_STEP, middle()),
    zoomOut: () => zoomAt(1 / KEY_STEP, middle()),
    fit: showWhole,
    over: () => pan.over,
    holdSpace: () => pan.holdSpace(),
  });

  return {
    get zoom() {
      return frame.width / view.width;
    },
    controls,
    fit: showWhole,
    onChange(listener) {
      listeners.add(listener);
      return () => listeners.delete(listener);
    },
    dispose() {
      removeKeys();
      listening.abort();
      controls.remove();
    },
  };
}
