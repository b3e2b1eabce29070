// Pointer presses on the photo, in image pixels, to the active photo tool. "Select" is the
// photo's own behaviour: it gets nothing here, so the photo's listeners get the events. Any
// other tool gets the primary button's presses, and clicks are kept from the photo's listeners.
import type { PhotoTool, PhotoToolHost } from "../photoTools";

/** The photo tools' state: the active tool and the pointer it is drawing with. */
export interface ToolState {
  active: PhotoTool;
  pressed: number | null;
}

/** Listen on the photo until `signal` aborts; `select` is the photo's own tool. */
export function routePointer(
  host: PhotoToolHost,
  state: ToolState,
  select: PhotoTool,
  signal: AbortSignal,
): void {
  const { svg } = host;
  const routed = (event: PointerEvent) => state.active !== select && event.isPrimary;
  const onDown = (event: PointerEvent) => {
    const { active } = state;
    if (!routed(event) || event.button !== 0 || !active.down) return;
    const at = host.toImage(event);
    if (!at) return;
    event.preventDefault();
    event.stopPropagation();
    state.pressed = event.pointerId;
    svg.setPointerCapture?.(event.pointerId);
    active.down(at, event);
  };
  const onMove = (event: PointerEvent) => {
    const { active } = state;
    if (!routed(event) || !active.move) return;
    const at = host.toImage(event);
    if (at) active.move(at, event);
  };
  const onUp = (event: PointerEvent) => {
    if (state.pressed !== event.pointerId) return;
    state.pressed = null;
    if (svg.hasPointerCapture?.(event.pointerId)) svg.releasePointerCapture(event.pointerId);
    const at = host.toImage(event);
    if (at && routed(event)) state.active.up?.(at, event);
  };
  const onClick = (event: MouseEvent) => {
    if (state.active !== select) event.stopPropagation();
  };
  // Capture phase: a tool's press is not also a click or drag for the photo's own listeners.
  svg.addEventListener("pointerdown", onDown, { capture: true, signal });
  svg.addEventListener("pointermove", onMove, { signal });
  svg.addEventListener("pointerup", onUp, { signal });
  svg.addEventListener("pointercancel", onUp, { signal });
  svg.addEventListener("click", onClick, { capture: true, signal });
}
