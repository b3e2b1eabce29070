// Whether the downloadable scene.glb shows the scene as it is now: the file is what the last
// pipeline or placement run made, so objects added, removed or redrawn since, or a room moved
// since, are not in it. The Download menu says so beside the file.
import type { SceneDocument } from "@holiscene/schema";
import { diffScenes } from "../../state/revisionDiff";
import { plural } from "../../state/sceneSession";

/** What the GLB made at revision `made` lacks of `current` (null: nothing it shows changed). */
export function glbStaleness(made: SceneDocument, current: SceneDocument): string | null {
  const diff = diffScenes(made.scene, current.scene);
  const redrawn = diff.objectsChanged.filter((c) => c.drawn.length > 0).length;
  const parts = [
    diff.objectsAdded.length > 0 && `${plural(diff.objectsAdded.length, "object")} added`,
    diff.objectsRemoved.length > 0 && `${diff.objectsRemoved.length} removed`,
    redrawn > 0 && `${redrawn} changed`,
    diff.layoutChanged && "the room moved",
  ].filter((part): part is string => typeof part === "string");
  if (parts.length === 0) return null;
  return (
    `made at revision ${made.revision}; since then ${parts.join(", ")}: ` +
    `"Re-place objects" in the 3D panel brings it up to date`
  );
}
