// Reverting to a revision: the whole scene (objects, supports, room layout, camera) goes back
// as that revision had it, as one object action: a new revision at once, which undo takes back.
import type { SceneDocument } from "@holiscene/schema";
import { type ObjectEditor, objectsChanged, WHOLE_SCENE } from "../../../state/objectEditor";
import { plural } from "../../../state/sceneSession";

/** Revert; resolves to why nothing was sent (null: sent, its outcome is the editor's). */
export async function revertTo(
  editor: ObjectEditor,
  number: number,
  target: SceneDocument,
): Promise<string | null> {
  const session = editor.session;
  const unsaved = session.unsavedCount;
  if (unsaved > 0) {
    // The revert would be saved under them: they would come back on top of the old scene.
    return `Save or discard your ${plural(unsaved, "unsaved change")} first: a revert replaces the whole scene.`;
  }
  if (objectsChanged([WHOLE_SCENE], target, session.doc).length === 0) {
    return `The scene is already as in revision ${number}.`;
  }
  editor.remember(target); // shown at once, before the server answers
  const label = `revert to revision ${number}`;
  await editor.apply([{ kind: "restore_scene", from_revision: number }], label);
  return null;
}
