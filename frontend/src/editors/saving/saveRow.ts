// The save bar's first line: the save status, Undo / Redo (of the last action, whichever
// history it is in, see state/undoOrder.ts), Discard and Save.
import { button, el } from "../../dom";
import { autosaveDelay } from "../../state/autosave";
import { plural, type SaveState, type SceneSession } from "../../state/sceneSession";
import { latestRedo, latestUndo, type Undoable } from "../../state/undoOrder";

/** How unsaved edits will be saved: by themselves, or only when the person says so (after a
 * conflict's "Reload: review first", with autosave turned off in this browser, or never while
 * no room fits the moved corners). */
export type SavingMode = "auto" | "held" | "undiscarded" | "off" | "unfit";

export function savingMode(session: SceneSession): SavingMode {
  if (!session.savable) return "unfit";
  if (session.holdAutosave === "undone discard") return "undiscarded";
  if (session.holdAutosave) return "held";
  return autosaveDelay() === 0 ? "off" : "auto";
}

const DIRTY_TAIL: Record<SavingMode, string> = {
  auto: "autosaving",
  held: "held after the reload: review, then Save (Ctrl+S)",
  undiscarded: "brought back by Undo after Discard, not saved: Save (Ctrl+S) keeps them",
  off: "autosave is off here: Save (Ctrl+S)",
  unfit: "not saved while no room fits the moved corners",
};

export function statusText(
  state: SaveState,
  pending: number,
  revision: number,
  mode: SavingMode,
  objectAction: string | null,
  objectFailed: string | null = null,
): string {
  // An object action saves on its own path: while it is out, or kept after it failed, "no
  // unsaved changes" or "Saved as revision N" would tell the annotator all is safe.
  if (state.kind === "clean" || state.kind === "saved") {
    if (objectAction !== null) return `Saving: ${objectAction}…`;
    if (objectFailed !== null) return `Not saved: ${objectFailed} (above the photo)`;
  }
  const failedToo = objectFailed === null ? "" : ` · not saved: ${objectFailed}`;
  return supportStatus(state, pending, revision, mode) + failedToo;
}

/** The support and layout edits' part of the status. */
function supportStatus(
  state: SaveState,
  pending: number,
  revision: number,
  mode: SavingMode,
): string {
  switch (state.kind) {
    case "clean":
      return `Revision ${revision} · no unsaved changes`;
    case "dirty":
      return `${plural(pending, "unsaved change")} on revision ${revision} · ${DIRTY_TAIL[mode]}`;
    case "saving":
      return "Saving…";
    case "saved":
      // Object actions save on their own path after this save: the latest revision is theirs.
      return `Saved as revision ${Math.max(state.revision, revision)}`;
    case "conflict":
      return "Not saved: conflict";
    case "error":
      return state.retry ? "Not saved: error (retrying)" : "Not saved: refused";
  }
}

export interface SaveRowInputs {
  session: SceneSession;
  /** The histories Undo and Redo choose from (the last action's). */
  histories: readonly Undoable[];
  undoLast(): void;
  redoLast(): void;
  saveNow(): void;
  /** The object action being saved, if one is (state/objectEditor.ts). */
  objectAction?: () => string | null;
  /** The object action kept after it failed, if one is. */
  objectFailed?: () => string | null;
}

export interface SaveRow {
  element: HTMLElement;
  save: HTMLButtonElement;
  update(): void;
}

export function saveRow({
  session,
  histories,
  undoLast,
  redoLast,
  saveNow,
  objectAction = () => null,
  objectFailed = () => null,
}: SaveRowInputs): SaveRow {
  const status = el("span", {
    className: "save-status",
    testid: "save-status",
    attrs: { role: "status", "aria-live": "polite" },
  });
  const undo = button("Undo", { testid: "undo-button", onClick: undoLast });
  const redo = button("Redo", { testid: "redo-button", onClick: redoLast });
  const save = button("Save", {
    className: "primary",
    testid: "save-button",
    title: "Save now (Ctrl+S); edits are also saved by themselves",
    onClick: saveNow,
  });
  const discard = button("Discard", {
    testid: "discard-button",
    title: "Drop the unsaved changes (undo brings them back)",
    onClick: () => session.discard(),
  });
  const actions = el("span", { className: "save-actions" }, undo, redo, discard, save);
  const element = el(
    "div",
    { className: "save-row" },
    status,
    // Together, at the right: beside the status when there is room, else all on the line
    // under it (not two here and two there).
    actions,
  );

  const update = () => {
    const state = session.saveState;
    const unsaved = session.unsavedCount;
    const editable = session.editable;
    const action = objectAction();
    const failed = objectFailed();
    const quiet = state.kind === "clean" || state.kind === "saved";
    status.textContent = statusText(
      state,
      unsaved,
      session.doc.revision,
      savingMode(session),
      action,
      failed,
    );
    status.dataset.state =
      action !== null && state.kind !== "saving"
        ? "saving-object"
        : failed !== null && quiet
          ? "object-failed"
          : state.kind;
    const busy = state.kind === "saving";
    save.disabled = !editable || busy || !session.savable || state.kind === "conflict";
    discard.disabled = !editable || busy || unsaved === 0;
    const undoLabel = latestUndo(histories)?.undoLabel ?? null;
    const redoLabel = latestRedo(histories)?.redoLabel ?? null;
    undo.disabled = !editable || undoLabel === null;
    redo.disabled = !editable || redoLabel === null;
    // Greyed buttons say nothing to a person who can only look: left out until there is
    // something unsaved to keep (a refused save's changes, kept for later).
    actions.hidden = session.viewOnly && unsaved === 0;
    undo.title = undoLabel ? `Undo: ${undoLabel} (Ctrl+Z)` : "Nothing to undo";
    redo.title = redoLabel ? `Redo: ${redoLabel} (Ctrl+Shift+Z)` : "Nothing to redo";
  };
  return { element, save, update };
}
