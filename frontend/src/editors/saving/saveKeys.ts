// The save bar's keys: undo, redo, save now, and the answers to a conflict and to edits a
// previous visit left unsaved. Each works only while the scene is editable.
import { registerShortcut } from "../../shortcuts";
import type { SceneSession } from "../../state/sceneSession";

export interface SaveKeyActions {
  undoLast(): void;
  redoLast(): void;
  /** Save now, if the Save button is enabled. */
  saveNow(): void;
  merge(): void;
  reload(): void;
}

/** Register the keys; returns the function that removes them. */
export function saveKeys(session: SceneSession, actions: SaveKeyActions): () => void {
  const scope = "Saving and history";
  const editable = () => session.editable;
  const inConflict = () => editable() && session.saveState.kind === "conflict";
  const removers = [
    registerShortcut({
      keys: ["Ctrl+Z"],
      description: "Undo the last edit (a support, a room corner or an object)",
      scope,
      enabled: editable,
      run: actions.undoLast,
    }),
    registerShortcut({
      keys: ["Ctrl+Shift+Z", "Ctrl+Y"],
      description: "Redo",
      scope,
      enabled: editable,
      run: actions.redoLast,
    }),
    registerShortcut({
      keys: "Ctrl+S",
      description: "Save now (edits are also saved after a short pause)",
      scope,
      enabled: editable,
      run: actions.saveNow,
    }),
    registerShortcut({
      keys: "Shift+M",
      description: "After a conflict: merge, saving your changes on top of theirs",
      scope,
      enabled: inConflict,
      run: actions.merge,
    }),
    registerShortcut({
      keys: "Shift+R",
      description: "After a conflict: reload their version, yours re-applied unsaved",
      scope,
      enabled: inConflict,
      run: actions.reload,
    }),
    registerShortcut({
      keys: "Shift+U",
      description: "Restore the changes your last visit left unsaved",
      scope,
      enabled: () => editable() && session.recovered !== null,
      run: () => session.restoreRecovered(),
    }),
  ];
  return () => {
    for (const remove of removers) remove();
  };
}
