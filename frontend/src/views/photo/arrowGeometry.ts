// Where support arrows go on the photo: from the supporter to the supported object. A
// structural supporter (floor, wall, ceiling) is a small labelled anchor next to the object.
import type { SceneObject } from "@holiscene/schema";
import type { StructuralSupporter } from "../../state/supportGraph";

export type Point = [number, number];

export interface Frame {
  width: number;
  height: number;
  /** Space around the photo where anchors may sit. */
  margin: number;
}

/** The margin around a photo of this size: room for anchors below or beside objects. */
export function frameFor(width: number, height: number): Frame {
  return { width, height, margin: Math.round(Math.max(width, height) * 0.06) };
}

/** Stroke width of arrows in image pixels, readable at any photo size. */
export function strokeWidth(frame: Frame): number {
  return Math.max(2, Math.max(frame.width, frame.height) / 260);
}

/**
 * The anchor of a structural supporter for `object` whose centroid is `centroid`: below the
 * object for the floor, above it for the ceiling, beside it for a wall. `labelHalf` is half the
 * size of the anchor's label, which is kept inside the frame.
 */
export function structuralAnchor(
  parent: StructuralSupporter,
  object: SceneObject,
  centroid: Point,
  frame: Frame,
  labelHalf: Point,
): Point {
  const [x1, y1, x2, y2] = object.bbox;
  const gap = frame.margin * 0.55;
  const clamp = (value: number, size: number, half: number) =>
    Math.min(size + frame.margin - half, Math.max(-frame.margin + half, value));
  const clampX = (x: number) => clamp(x, frame.width, labelHalf[0]);
  const clampY = (y: number) => clamp(y, frame.height, labelHalf[1]);
  switch (parent) {
    case "floor":
      return [clampX(centroid[0]), clampY(Math.max(y2 + gap, centroid[1] + gap))];
    case "ceiling":
      return [clampX(centroid[0]), clampY(Math.min(y1 - gap, centroid[1] - gap))];
    case "wall": {
      // Beside the object, on the side facing the nearer edge of the photo.
      const left = centroid[0] < frame.width / 2;
      const x = left
        ? Math.min(x1 - gap, centroid[0] - gap)
        : Math.max(x2 + gap, centroid[0] + gap);
      return [clampX(x), clampY(centroid[1])];
    }
  }
}

export interface ArrowShape {
  /** Path of the shaft. */
  shaft: string;
  /** Closed path of the head, its tip at the end point. */
  head: string;
}

/** A straight arrow from `from` to `to`, the start pulled in by `startGap`. */
export function arrowShape(from: Point, to: Point, width: number, startGap = 0): ArrowShape {
  const dx = to[0] - from[0];
  const dy = to[1] - from[1];
  const length = Math.hypot(dx, dy) || 1;
  const ux = dx / length;
  const uy = dy / length;
  const headLength = Math.min(width * 5, length * 0.5);
  const headHalf = width * 2.4;
  const start: Point = [from[0] + ux * startGap, from[1] + uy * startGap];
  const base: Point = [to[0] - ux * headLength, to[1] - uy * headLength];
  const fmt = (p: Point) => `${p[0].toFixed(1)} ${p[1].toFixed(1)}`;
  const wing = (sign: number): Point => [
    base[0] - uy * headHalf * sign,
    base[1] + ux * headHalf * sign,
  ];
  return {
    shaft: `M ${fmt(start)} L ${fmt(base)}`,
    head: `M ${fmt(to)} L ${fmt(wing(1))} L ${fmt(wing(-1))} Z`,
  };
}

/** An object supporter as the arrows see it: its box and, if it has one, its mask's pixels. */
export interface SupporterShape {
  bbox: readonly [number, number, number, number];
  /** The mask's window (origin, size) and its pixels, one byte each, row by row. */
  mask: {
    origin: readonly [number, number];
    size: readonly [number, number];
    bits: Uint8Array;
  } | null;
  centroid: Point;
}

/**
 * Where the arrow from an object supporter to a child starts. From below: the supporter's pixel
 * under the child's middle nearest the child's bottom (a book's shelf board, a lamp's table
 * top), so the arrows of a shelf's children start apart instead of fanning out of its centre.
 * From behind, or with no supporter pixel in that column below the child's centre, its centre. The start is kept at
 * least `minLength` from the child's centre (pushed straight down from it if they meet).
 */
export function arrowFoot(
  type: string,
  childBox: readonly [number, number, number, number],
  childCentre: Point,
  supporter: SupporterShape,
  minLength: number,
): Point {
  const foot = type === "below" ? footBelow(childBox, childCentre, supporter) : null;
  if (!foot) return supporter.centroid;
  const dx = foot[0] - childCentre[0];
  const dy = foot[1] - childCentre[1];
  const length = Math.hypot(dx, dy);
  if (length >= minLength) return foot;
  if (length < 1e-6) return [childCentre[0], childCentre[1] + minLength];
  return [childCentre[0] + (dx / length) * minLength, childCentre[1] + (dy / length) * minLength];
}

function footBelow(
  childBox: readonly [number, number, number, number],
  childCentre: Point,
  { bbox, mask }: SupporterShape,
): Point | null {
  const [sx1, , sx2] = bbox;
  if (sx2 <= sx1) return null;
  const x = Math.min(sx2 - 0.5, Math.max(sx1 + 0.5, childCentre[0]));
  const bottom = childBox[3];
  if (!mask) return [x, Math.min(bbox[3], Math.max(bbox[1], bottom, childCentre[1]))];
  const [ox, oy] = mask.origin;
  const [width, height] = mask.size;
  // Only pixels below the child's centre: an arrow from below points up.
  const firstRow = Math.max(0, Math.ceil(childCentre[1] - oy - 0.5));
  const column = Math.floor(x) - ox;
  if (column >= 0 && column < width) {
    let best: number | null = null;
    for (let row = firstRow; row < height; row++) {
      if (!mask.bits[row * width + column]) continue;
      const y = oy + row + 0.5;
      if (best === null || Math.abs(y - bottom) < Math.abs(best - bottom)) best = y;
    }
    if (best !== null) return [x, best];
  }
  // Nothing of the supporter shows under the child's middle (the child covers it down to the
  // supporter's edge): its pixel nearest the child's bottom middle, still below the centre.
  let nearest: Point | null = null;
  let nearestDistance = Number.POSITIVE_INFINITY;
  for (let row = firstRow; row < height; row++) {
    const y = oy + row + 0.5;
    for (let col = 0; col < width; col++) {
      if (!mask.bits[row * width + col]) continue;
      const px = ox + col + 0.5;
      const distance = (px - childCentre[0]) ** 2 + (y - bottom) ** 2;
      if (distance < nearestDistance) {
        nearestDistance = distance;
        nearest = [px, y];
      }
    }
  }
  return nearest;
}
