// Accepting suggested boxes: they become objects in one add_object request (one undoable
// action; after a conflict the object editor sends it again on the latest revision), and the
// server answers with the new revision, their masks cut.

import { classText } from "../../../state/classNames";
import type { ObjectEditor } from "../../../state/objectEditor";
import { plural } from "../../../state/sceneSession";
import { addObjectEdit, type Offer, offerLabel } from "../detectionOffers";

/** What the status line says while offers are being added. */
export function addingText(chosen: readonly Offer[]): string {
  return chosen.length === 1
    ? `Adding ${offerLabel(chosen[0] as Offer)}…`
    : `Adding ${plural(chosen.length, "object")}…`;
}

// Up to this many new objects are named one by one; more are counted per class (a list of 60
// names is unreadable, in the status line and in the undo history alike).
const NAMED_AT_MOST = 4;

/** "d3 (chair), d4 (lamp)", or for many "61 objects (54 chair, 5 sofa, 2 otherprop)". */
export function addedObjectsText(added: readonly { id: string; class: string }[]): string {
  if (added.length <= NAMED_AT_MOST)
    return added.map((a) => `${a.id} (${classText(a.class)})`).join(", ");
  const perClass = new Map<string, number>();
  for (const a of added) perClass.set(a.class, (perClass.get(a.class) ?? 0) + 1);
  const counts = [...perClass]
    .sort((x, y) => y[1] - x[1] || x[0].localeCompare(y[0]))
    .map(([cls, count]) => `${count} ${cls}`);
  return `${plural(added.length, "object")} (${counts.join(", ")})`;
}

/** Add the offers as objects; `names` says what was added (addedObjectsText). */
export async function addOffers(
  editor: ObjectEditor,
  chosen: readonly Offer[],
): Promise<{ saved: boolean; names: string }> {
  const ids = editor.newObjectIds(chosen.length);
  const edits = chosen.map((offer, i) => addObjectEdit(offer, ids[i] as string));
  const names = addedObjectsText(edits);
  const saved = await editor.apply(edits, `add ${names}`);
  return { saved, names };
}
