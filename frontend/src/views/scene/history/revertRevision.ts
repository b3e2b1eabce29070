// Reverting to a revision: the whole scene (objects, supports, room layout, camera) goes back
// as that revision had it, as one object action: a new revision at once, which undo takes back.
import type { SceneDocument } from "@holiscene/schema";
import { type ObjectEditor, objectsChanged, WHOLE_SCENE } from "../../../state/objectEditor";
import { plural } from "../../../state/sceneSession";

export async function revertTo(
  editor: ObjectEditor,
  number: number,
  target: SceneDocument,
): Promise<void> {
  const session = editor.session;
  const unsaved = session.unsavedCount;
  if (unsaved > 0) {
    // The revert would be saved under them: they would come back on top of the old scene.
    session.say(
      `Save or discard your ${plural(unsaved, "unsaved change")} first: a revert replaces the whole scene.`,
    );
    return;
  }
  if (objectsChanged([WHOLE_SCENE], target, session.doc).length === 0) {
    session.say(`The scene is already as in revision ${number}.`);
    return;
  }
  editor.remember(target); // shown at once, before the server answers
  await editor.apply(
    [{ kind: "restore_scene", from_revision: number }],
    `revert to revision ${number}`,
  );
}
