// Where the layout editor draws its corner handles. A corner on the photo or in the margin
// around it has its handle on it. A corner further out (a ceiling corner above the frame, a
// near corner beside it) has its handle on the edge of the drawing, at the point nearest to
// the corner, with an arrow pointing at it; dragging that handle moves the corner by as much
// as the pointer moves (along the edge the handle slides with the pointer; across the edge
// the corner comes nearer or goes further out).
import type { Point2 } from "../../geometry/camera";
import type { Frame } from "./arrowGeometry";

export interface Rect {
  left: number;
  top: number;
  right: number;
  bottom: number;
}

export interface PlacedHandle {
  index: number;
  /** The corner itself, possibly far off the photo. */
  corner: Point2;
  /** Whether the fit goes through the corner (see LayoutDraft.handles). */
  pinned: boolean;
  /** Where the handle is drawn. */
  at: Point2;
  /** The corner is beyond the drawing: the handle is on its edge, pointing at the corner. */
  clamped: boolean;
  /** Unit vector from the handle towards the corner (clamped handles only). */
  direction: Point2 | null;
}

/** The drawing over a photo: the photo and the margin around it (image pixels). */
export function drawingRect(frame: Frame): Rect {
  const { width, height, margin } = frame;
  return { left: -margin, top: -margin, right: width + margin, bottom: height + margin };
}

/** The point of the rectangle nearest to `p`. */
export function clampToRect([x, y]: Point2, r: Rect): Point2 {
  return [Math.min(r.right, Math.max(r.left, x)), Math.min(r.bottom, Math.max(r.top, y))];
}

export const insideRect = ([x, y]: Point2, r: Rect): boolean =>
  x >= r.left && x <= r.right && y >= r.top && y <= r.bottom;

export function insetRect(r: Rect, by: number): Rect {
  return { left: r.left + by, top: r.top + by, right: r.right - by, bottom: r.bottom - by };
}

/**
 * Place the handles: a corner inside `area` (the drawing) gets its handle on it; one outside
 * gets it on the nearest point of `border` (the area inset by a handle's radius, so the handle
 * shows whole). Clamped handles closer than `spacing` to one placed before slide along the
 * edge, towards the middle, until they are apart.
 */
export function placeHandles(
  handles: readonly { index: number; point: Point2; pinned: boolean }[],
  area: Rect,
  border: Rect,
  spacing: number,
): PlacedHandle[] {
  const placed: PlacedHandle[] = [];
  const free = (p: Point2) =>
    placed.every((h) => Math.hypot(h.at[0] - p[0], h.at[1] - p[1]) >= spacing - 1e-9);
  // In-photo handles first: they stay where their corners are; clamped ones move aside.
  const ordered = [
    ...handles.filter((h) => insideRect(h.point, area)),
    ...handles.filter((h) => !insideRect(h.point, area)),
  ];
  for (const { index, point, pinned } of ordered) {
    if (insideRect(point, area)) {
      placed.push({ index, corner: point, pinned, at: point, clamped: false, direction: null });
      continue;
    }
    let at = clampToRect(point, border);
    const beyondX = Math.max(border.left - point[0], point[0] - border.right, 0);
    const beyondY = Math.max(border.top - point[1], point[1] - border.bottom, 0);
    // Slide along the edge the corner is mostly beyond (at a corner of the drawing: along the
    // side whose overshoot is larger), towards the middle of that edge.
    const along: 0 | 1 = beyondY >= beyondX ? 0 : 1;
    const middle =
      along === 0 ? (border.left + border.right) / 2 : (border.top + border.bottom) / 2;
    const step = (at[along] <= middle ? 1 : -1) * spacing;
    for (let tries = 0; tries < 12 && !free(at); tries++) {
      const next: Point2 = [at[0], at[1]];
      next[along] += step;
      at = clampToRect(next, border);
    }
    placed.push({ index, corner: point, pinned, at, clamped: true, direction: towards(at, point) });
  }
  return placed.sort((a, b) => a.index - b.index);
}

/**
 * A clamped handle while it is dragged: it follows the pointer (it was at `grabbedAt` when the
 * corner was at `grabbedCorner`, and the corner moved as the pointer did), kept inside the
 * drawing, still pointing at the corner.
 */
export function followPointer(
  handle: PlacedHandle,
  grabbedAt: Point2,
  grabbedCorner: Point2,
  border: Rect,
): PlacedHandle {
  if (!handle.clamped) return handle;
  const at = clampToRect(draggedCorner(grabbedAt, grabbedCorner, handle.corner), border);
  return { ...handle, at, direction: towards(at, handle.corner) };
}

/** The unit vector from `from` towards `to`. */
function towards(from: Point2, to: Point2): Point2 {
  const dx = to[0] - from[0];
  const dy = to[1] - from[1];
  const length = Math.hypot(dx, dy) || 1;
  return [dx / length, dy / length];
}

/** Where a point off the photo lies, in words: "off the photo: 420 px up, 30 px left". */
export function offPhotoText([x, y]: Point2, width: number, height: number): string {
  const parts: string[] = [];
  if (y < 0) parts.push(`${Math.round(-y)} px up`);
  if (y > height) parts.push(`${Math.round(y - height)} px down`);
  if (x < 0) parts.push(`${Math.round(-x)} px left`);
  if (x > width) parts.push(`${Math.round(x - width)} px right`);
  return parts.length === 0 ? "on the photo" : `off the photo: ${parts.join(", ")}`;
}

/** A dragged corner: where it was grabbed plus how far the pointer went since. */
export function draggedCorner(corner: Point2, grabbedAt: Point2, pointer: Point2): Point2 {
  return [corner[0] + pointer[0] - grabbedAt[0], corner[1] + pointer[1] - grabbedAt[1]];
}
