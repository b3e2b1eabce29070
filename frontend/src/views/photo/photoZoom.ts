// Zoom and pan of the photo by its SVG viewBox (hit-testing goes through getScreenCTM, so it
// keeps working): the wheel zooms about the pointer, a drag with the middle button or with
// Space held pans, + and - zoom about the middle, 0 fits the whole photo again. The view never
// leaves the photo's frame and is never smaller than it (arrows and labels, drawn in image
// pixels, only get larger); tools size their handles by the screen (host.pixelSize).
import { button, el } from "../../dom";
import { registerShortcut } from "../../shortcuts";

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
  let pan: { id: number; x: number; y: number } | null = null;
  let spaceHeld = false;
  let over = false;
  const listeners = new Set<() => void>();
  /** The cursor before Space or a pan showed the hand (the active tool's). */
  let toolCursor: string | null = null;
  const showHand = (cursor: "grab" | "grabbing" | null) => {
    if (cursor && toolCursor === null) toolCursor = svg.style.cursor;
    svg.style.cursor = cursor ?? toolCursor ?? "";
    if (!cursor) toolCursor = null;
  };

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
  const toImage = (event: MouseEvent): [number, number] | null => {
    const matrix = svg.getScreenCTM();
    if (!matrix) return null;
    const p = new DOMPoint(event.clientX, event.clientY).matrixTransform(matrix.inverse());
    return [p.x, p.y];
  };

  const onWheel = (event: WheelEvent) => {
    const at = toImage(event);
    if (!at) return;
    event.preventDefault(); // the page does not scroll while the photo zooms
    const lines = event.deltaMode === 1 ? 16 : 1;
    zoomAt(Math.exp(-event.deltaY * lines * WHEEL_RATE), at);
  };
  const onDown = (event: PointerEvent) => {
    if (!(event.button === 1 || (event.button === 0 && spaceHeld))) return;
    event.preventDefault();
    event.stopImmediatePropagation(); // a pan is not a click, a drawing or an arrow drag
    pan = { id: event.pointerId, x: event.clientX, y: event.clientY };
    svg.setPointerCapture?.(event.pointerId);
    showHand("grabbing");
  };
  const onMove = (event: PointerEvent) => {
    if (!pan || event.pointerId !== pan.id) return;
    const scale = svg.getScreenCTM()?.a || 1; // screen pixels per image pixel
    const dx = (event.clientX - pan.x) / scale;
    const dy = (event.clientY - pan.y) / scale;
    pan = { ...pan, x: event.clientX, y: event.clientY };
    event.stopImmediatePropagation();
    apply(clampView(frame, { ...view, x: view.x - dx, y: view.y - dy }));
  };
  const onUp = (event: PointerEvent) => {
    if (!pan || event.pointerId !== pan.id) return;
    pan = null;
    event.stopImmediatePropagation();
    showHand(spaceHeld ? "grab" : null);
  };
  // The middle button's click would paste or open a link on some systems.
  const onAux = (event: MouseEvent) => {
    if (event.button === 1) event.preventDefault();
  };
  const onKeyUp = (event: KeyboardEvent) => {
    if (event.key === " ") {
      spaceHeld = false;
      if (!pan) showHand(null);
    }
  };
  const onEnter = () => {
    over = true;
  };
  const onLeave = () => {
    over = false;
  };
  // One signal takes every listener off again in dispose().
  const listening = new AbortController();
  const { signal } = listening;
  svg.addEventListener("wheel", onWheel, { passive: false, signal });
  svg.addEventListener("pointerdown", onDown, { capture: true, signal });
  svg.addEventListener("pointermove", onMove, { capture: true, signal });
  svg.addEventListener("pointerup", onUp, { capture: true, signal });
  svg.addEventListener("auxclick", onAux, { signal });
  svg.addEventListener("pointerenter", onEnter, { signal });
  svg.addEventListener("pointerleave", onLeave, { signal });
  window.addEventListener("keyup", onKeyUp, { signal });

  const scope = "Photo";
  const removers = [
    registerShortcut({
      keys: ["+", "="],
      description: "Zoom the photo in (the wheel zooms about the pointer)",
      scope,
      run: () => zoomAt(KEY_STEP, middle()),
    }),
    registerShortcut({
      keys: "-",
      description: "Zoom the photo out",
      scope,
      run: () => zoomAt(1 / KEY_STEP, middle()),
    }),
    registerShortcut({
      keys: "0",
      description: "Fit the whole photo",
      scope,
      run: showWhole,
    }),
    registerShortcut({
      keys: "Space",
      description: "Hold over the photo and drag to pan (or drag with the middle button)",
      scope,
      // Only over the photo: elsewhere Space keeps scrolling the page and pressing buttons.
      enabled: () => over,
      run: () => {
        spaceHeld = true;
        if (!pan) showHand("grab");
      },
    }),
  ];

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
      for (const remove of removers) remove();
      listening.abort();
      controls.remove();
    },
  };
}
