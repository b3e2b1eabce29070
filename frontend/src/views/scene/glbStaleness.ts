// Whether the downloadable scene.glb shows the scene as it is now: the file is what the last
// pipeline or placement run made, so objects added, removed or redrawn since, or a room moved
// since, are not in it. The Download menu says so beside the file, counted as the 3D panel's
// notice counts them (scene3d/placementNotice.ts).
import type { SceneDocument } from "@holiscene/schema";
import { diffScenes } from "../../state/revisionDiff";
import { changesSincePlacement, describeChanges } from "../scene3d/placementNotice";

/** What the GLB made at revision `made` lacks of `current` (null: nothing it shows changed). */
export function glbStaleness(made: SceneDocument, current: SceneDocument): string | null {
  const objects = describeChanges(changesSincePlacement(made.scene.objects, current.scene.objects));
  const moved = diffScenes(made.scene, current.scene).layoutChanged;
  const parts = [objects, moved ? "the room moved" : ""].filter((part) => part !== "");
  if (parts.length === 0) return null;
  return (
    `made at revision ${made.revision}; since then ${parts.join(", ")}: ` +
    `"Re-place objects" in the 3D panel brings it up to date`
  );
}
