// Panning the zoomed photo: a drag with the middle button, or with the primary one while Space
// is held over the photo (the cursor shows a hand meanwhile). A pan's press goes to nobody
// else: no click, drawing or arrow drag comes of it.
export interface PhotoPan {
  /** The pointer is over the photo. */
  readonly over: boolean;
  /** Space went down over the photo: the next primary drag pans. */
  holdSpace(): void;
}

/** Listen on `svg` until `signal` aborts; `moveBy` hears each step in photo pixels. */
export function photoPan(
  svg: SVGSVGElement,
  moveBy: (dx: number, dy: number) => void,
  signal: AbortSignal,
): PhotoPan {
  let pan: { id: number; x: number; y: number } | null = null;
  let spaceHeld = false;
  let over = false;
  /** The cursor before Space or a pan showed the hand (the active tool's). */
  let toolCursor: string | null = null;
  const showHand = (cursor: "grab" | "grabbing" | null) => {
    if (cursor && toolCursor === null) toolCursor = svg.style.cursor;
    svg.style.cursor = cursor ?? toolCursor ?? "";
    if (!cursor) toolCursor = null;
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
    moveBy(dx, dy);
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
  svg.addEventListener("pointerdown", onDown, { capture: true, signal });
  svg.addEventListener("pointermove", onMove, { capture: true, signal });
  svg.addEventListener("pointerup", onUp, { capture: true, signal });
  svg.addEventListener("auxclick", onAux, { signal });
  svg.addEventListener("pointerenter", () => (over = true), { signal });
  svg.addEventListener("pointerleave", () => (over = false), { signal });
  window.addEventListener("keyup", onKeyUp, { signal });
  return {
    get over() {
      return over;
    },
    holdSpace() {
      spaceHeld = true;
      if (!pan) showHand("grab");
    },
  };
}
