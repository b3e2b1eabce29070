// What changed of the objects since the 3D scene was made: placement reads each object's class,
// 2D box and mask, so objects added, removed or changed in those since the last placement (or
// pipeline) run are not in the 3D scene as they are now.
import type { SceneObject } from "@holiscene/schema";
import { plural } from "../../state/sceneSession";
import { isStructural } from "../../state/supportGraph";

export interface PlacementChanges {
  added: string[];
  removed: string[];
  changed: string[];
}

/** What placement reads of an object (its 2D evidence). */
const placementInput = (o: SceneObject) => JSON.stringify([o.class, o.bbox, o.mask ?? null]);

/**
 * Whether `next` comes from a placement run after `previous`: an object of both has a new 3D
 * box (object edits never touch 3D boxes; an undone removal brings back the old one).
 */
export function newlyPlaced(previous: readonly SceneObject[], next: readonly SceneObject[]) {
  const before = new Map(previous.map((o) => [o.id, JSON.stringify(o.box_3d ?? null)]));
  return next.some((o) => {
    const old = before.get(o.id);
    return old !== undefined && o.box_3d != null && old !== JSON.stringify(o.box_3d);
  });
}

/**
 * The objects that differ between the ones the 3D scene was made from (`placed`) and the
 * current ones. An object a person added that has no 3D box yet counts as added even when
 * it was already there when the page opened (the notice comes back after a reload), unless
 * `placedByRun`: `placed` is a placement or pipeline run's own result, which tried it and
 * could not place it (placing it again would not either; its stage note says why).
 */
export function changesSincePlacement(
  placed: readonly SceneObject[],
  current: readonly SceneObject[],
  placedByRun = false,
): PlacementChanges {
  const movable = (objects: readonly SceneObject[]) =>
    objects.filter((o) => !isStructural(o.class));
  const before = new Map(movable(placed).map((o) => [o.id, o]));
  const now = movable(current);
  const nowIds = new Set(now.map((o) => o.id));
  const added: string[] = [];
  const changed: string[] = [];
  for (const object of now) {
    const old = before.get(object.id);
    const unplaced =
      !placedByRun && !object.box_3d && (object.set_by_person ?? []).includes("object");
    if (!old || unplaced) added.push(object.id);
    else if (placementInput(old) !== placementInput(object)) changed.push(object.id);
  }
  const removed = [...before.keys()].filter((id) => !nowIds.has(id));
  return { added, removed, changed };
}

export function describeChanges({ added, removed, changed }: PlacementChanges): string {
  const parts = [
    added.length > 0 && `${plural(added.length, "object")} added`,
    removed.length > 0 && `${removed.length} removed`,
    changed.length > 0 && `${changed.length} changed`,
  ].filter(Boolean);
  return parts.join(", ");
}
