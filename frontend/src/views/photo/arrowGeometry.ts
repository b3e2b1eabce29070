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
