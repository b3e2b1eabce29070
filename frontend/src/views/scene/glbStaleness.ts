// Whether the scene's scene.glb shows the scene as it is now: the file is what the last
// pipeline or placement run made, so objects added, removed or redrawn since, or a room moved
// since, are not in it. Told alike by the Download menu (beside the file), the 3D panel's
// notice (which counts from the revision that made the file) and the workflow bar (before a
// submit or an accept, after which nobody can re-place the objects).
import type { Scene, SceneDocument } from "@holiscene/schema";
import { api } from "../../api/client";
import { glbRevision } from "../../api/downloads";
import { diffScenes } from "../../state/revisionDiff";
import { changesSincePlacement, describeChanges } from "../scene3d/placementChanges";
import { mayHaveGlb } from "../scene3d/viewportObjects";

/** What a GLB made from scene `made` lacks of `current` ("" when nothing it shows changed);
 * `madeByRun`: `made` is a run's result, as a scene.glb's own revision always is. */
export function glbLacks(made: Scene, current: Scene, madeByRun = true): string {
  const objects = describeChanges(changesSincePlacement(made.objects, current.objects, madeByRun));
  const moved = diffScenes(made, current).layoutChanged;
  return [objects, moved ? "the room moved" : ""].filter((part) => part !== "").join(", ");
}

/** The Download menu's line for an outdated file (null: it shows the scene as it is). */
export function glbStaleness(
  made: SceneDocument,
  current: SceneDocument,
  editable = true,
): string | null {
  const lacks = glbLacks(made.scene, current.scene);
  if (lacks === "") return null;
  const remedy = editable
    ? `"Re-place objects" in the 3D panel brings it up to date`
    : "it can be re-placed only while the scene is being annotated";
  return `made at revision ${made.revision}; since then ${lacks}: ${remedy}`;
}

/**
 * The revision that made the scene's scene.glb: `current` itself when it was made there (a
 * run's revision), null when there is no file.
 */
export async function glbSourceRevision(
  sceneId: string,
  current: SceneDocument,
  signal?: AbortSignal,
): Promise<SceneDocument | null> {
  if (!mayHaveGlb(current)) return null;
  const made = await glbRevision(sceneId, signal);
  if (made === null) return null;
  if (!(made < current.revision)) return current;
  return api.getRevision(sceneId, made, signal);
}

/** What the scene's scene.glb lacks of `current` ("" when it is up to date, or there is none). */
export async function glbOutOfDate(
  sceneId: string,
  current: SceneDocument,
  signal?: AbortSignal,
): Promise<string> {
  const made = await glbSourceRevision(sceneId, current, signal);
  return made ? glbLacks(made.scene, current.scene) : "";
}
