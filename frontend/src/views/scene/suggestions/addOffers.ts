// Accepting suggested boxes: they become objects in one add_object request (one undoable
// action; after a conflict the object editor sends it again on the latest revision), and the
// server answers with the new revision, their masks cut.
import type { ObjectEditor } from "../../../state/objectEditor";
import { plural } from "../../../state/sceneSession";
import { addObjectEdit, type Offer, offerLabel } from "../detectionOffers";

/** What the status line says while offers are being added. */
export function addingText(chosen: readonly Offer[]): string {
  return chosen.length === 1
    ? `Adding ${offerLabel(chosen[0] as Offer)}…`
    : `Adding ${plural(chosen.length, "object")}…`;
}

/** Add the offers as objects; `names` lists them as "d3 (chair), d4 (lamp)". */
export async function addOffers(
  editor: ObjectEditor,
  chosen: readonly Offer[],
): Promise<{ saved: boolean; names: string }> {
  const ids = editor.newObjectIds(chosen.length);
  const edits = chosen.map((offer, i) => addObjectEdit(offer, ids[i] as string));
  const names = edits.map((e) => `${e.id} (${e.class})`).join(", ");
  const saved = await editor.apply(edits, `add ${names}`);
  return { saved, names };
}
