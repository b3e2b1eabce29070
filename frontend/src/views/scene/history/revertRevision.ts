// Reverting to a revision: the supports go back exactly as that revision stored them, as one
// edit of the session (saved at once: a new revision, which undo takes back).
import type { SceneDocument } from "@holiscene/schema";
import { getAuthor } from "../../../state/author";
import { revertEdits } from "../../../state/revisionDiff";
import type { SceneSession } from "../../../state/sceneSession";

export async function revertTo(
  session: SceneSession,
  number: number,
  target: SceneDocument,
): Promise<void> {
  const shown = [...session.shown().values()].map(
    (s) =>
      s.saved ?? {
        child: s.child,
        parent: s.parent,
        type: s.type,
        source: s.source,
        author: s.author,
        time: s.time,
        confidence: s.confidence,
      },
  );
  const edits = revertEdits(session.doc.scene, shown, number, target.scene);
  if (edits.length === 0) {
    session.say(`The supports are already as in revision ${number}.`);
    return;
  }
  session.edit(`revert to revision ${number}`, edits);
  await session.save(getAuthor());
}
