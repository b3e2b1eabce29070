// The order of the objects in a supporter menu: nearest first, measured on the photo from the
// object's foot (the middle of its box's bottom edge) to each other object's box (0 when the
// foot is inside it). What holds an object up is almost always at its foot, so in a crowded
// room (ten "books" in a menu of 30) the likely supporters come first instead of by id.
import type { SceneObject } from "@holiscene/schema";

type Boxed = Pick<SceneObject, "id" | "bbox">;

/** Distance (pixels) from a point to a box, 0 inside it. */
function toBox([x, y]: readonly [number, number], bbox: readonly number[]): number {
  const [x0 = 0, y0 = 0, x1 = 0, y1 = 0] = bbox;
  const dx = Math.max(x0 - x, 0, x - x1);
  const dy = Math.max(y0 - y, 0, y - y1);
  return Math.hypot(dx, dy);
}

/** `others` ordered by their distance from `object`'s foot, nearest first (ties by id). */
export function nearestFirst<T extends Boxed>(object: Boxed, others: readonly T[]): T[] {
  const [x0 = 0, , x1 = 0, y1 = 0] = object.bbox;
  const foot: [number, number] = [(x0 + x1) / 2, y1];
  return others
    .map((other) => ({ other, distance: toBox(foot, other.bbox) }))
    .sort(
      (a, b) =>
        a.distance - b.distance || a.other.id.localeCompare(b.other.id, "en", { numeric: true }),
    )
    .map(({ other }) => other);
}
