// Saving: status, Undo / Redo (of the last action: an unsaved support or layout edit, or a
// saved object action, see state/undoOrder.ts), Save / Discard, the list of unsaved edits, edits a previous
// visit left unsaved (restore or discard), and the conflict message with its merge and reload
// actions. Edits are autosaved (state/autosave.ts) and kept in localStorage until the server
// has them, so leaving the page needs no warning: nothing is lost.
import { button, el } from "../dom";
import { registerShortcut } from "../shortcuts";
import { getAuthor } from "../state/author";
import type { ObjectEditor } from "../state/objectEditor";
import { plural, type SaveState, type SceneSession } from "../state/sceneSession";
import { describeEdit } from "../state/supportGraph";
import { latestRedo, latestUndo } from "../state/undoOrder";

/** The room layout's line in the lists of unsaved changes. */
const LAYOUT_CHANGE = "room layout changed (corners or camera height)";

function statusText(state: SaveState, pending: number, revision: number, savable: boolean): string {
  switch (state.kind) {
    case "clean":
      return `Revision ${revision} · no unsaved changes`;
    case "dirty":
      return (
        `${plural(pending, "unsaved change")} on revision ${revision} · ` +
        (savable ? "autosaving" : "not saved while no room fits the moved corners")
      );
    case "saving":
      return "Saving…";
    case "saved":
      return `Saved as revision ${state.revision}`;
    case "conflict":
      return "Not saved: conflict";
    case "error":
      return state.retry ? "Not saved: error (retrying)" : "Not saved: refused";
  }
}

function conflictText(state: Extract<SaveState, { kind: "conflict" }>, pending: number): string {
  const latest =
    state.currentRevision === null ? "" : ` (the latest is revision ${state.currentRevision})`;
  const who = [...new Set(state.theirs.map((r) => r.author))].join(", ") || "Someone else";
  return (
    `${who} saved this scene after you loaded revision ${state.baseRevision}${latest}. ` +
    `Your ${plural(pending, "change")} ${pending === 1 ? "was" : "were"} not saved and ` +
    `${pending === 1 ? "is" : "are"} kept (listed below, and in this browser). Merge to save ` +
    `yours on top of theirs, or reload to look at theirs first with yours re-applied unsaved.`
  );
}

export function mountSaveBar(
  container: HTMLElement,
  session: SceneSession,
  objects: ObjectEditor | null = null,
): () => void {
  const author = () => getAuthor();
  const histories = objects ? [session, objects] : [session];
  const undoLast = () => void latestUndo(histories)?.undo();
  const redoLast = () => void latestRedo(histories)?.redo();
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
    onClick: () => void session.save(author()),
  });
  const discard = button("Discard", {
    testid: "discard-button",
    title: "Drop the unsaved changes (undo brings them back)",
    onClick: () => session.discard(),
  });

  const conflictMessage = el("p", { testid: "conflict-text" });
  const theirsList = el("ul", { className: "conflict-theirs", testid: "conflict-theirs" });
  const merge = button("Merge: save mine on top (Shift+M)", {
    className: "primary",
    testid: "conflict-merge",
    onClick: () => void session.merge(author()),
  });
  const reload = button("Reload: review first (Shift+R)", {
    testid: "conflict-reload",
    onClick: () => void session.reloadLatest({ hold: true }),
  });
  const conflict = el(
    "div",
    { className: "alert alert--conflict", testid: "conflict-message", attrs: { role: "alert" } },
    el("strong", { text: "Conflict: your changes were not saved." }),
    conflictMessage,
    theirsList,
    el("div", { className: "save-row" }, merge, reload),
  );

  const recoveryText = el("span", { testid: "recovery-text" });
  const restore = button("Restore them (Shift+U)", {
    className: "primary",
    testid: "recovery-restore",
    onClick: () => session.restoreRecovered(),
  });
  const recovery = el(
    "div",
    { className: "alert alert--info", testid: "recovery-banner", attrs: { role: "alert" } },
    recoveryText,
    el(
      "div",
      { className: "save-row" },
      restore,
      button("Discard them", {
        testid: "recovery-discard",
        onClick: () => session.dismissRecovered(),
      }),
    ),
  );

  const error = el("div", {
    className: "alert alert--error",
    testid: "save-error",
    attrs: { role: "alert" },
  });
  const notice = el("p", { className: "alert alert--info", testid: "reload-notice" });
  const pendingItems = el("ul");
  const pendingList = el(
    "div",
    { className: "pending-list", testid: "pending-edits" },
    el("strong", { text: "Unsaved changes" }),
    pendingItems,
  );
  container.replaceChildren(
    el(
      "div",
      { className: "save-row" },
      status,
      el("span", { className: "spacer" }),
      undo,
      redo,
      discard,
      save,
    ),
    recovery,
    conflict,
    error,
    notice,
    pendingList,
  );

  const update = () => {
    const state = session.saveState;
    const pending = session.pending;
    const unsaved = session.unsavedCount;
    const editable = session.editable;
    status.textContent = statusText(state, unsaved, session.doc.revision, session.savable);
    status.dataset.state = state.kind;
    container.dataset.state = state.kind;
    const busy = state.kind === "saving";
    save.disabled = !editable || busy || !session.savable || state.kind === "conflict";
    discard.disabled = !editable || busy || unsaved === 0;
    const undoLabel = latestUndo(histories)?.undoLabel ?? null;
    const redoLabel = latestRedo(histories)?.redoLabel ?? null;
    undo.disabled = !editable || undoLabel === null;
    redo.disabled = !editable || redoLabel === null;
    undo.title = undoLabel ? `Undo: ${undoLabel} (Ctrl+Z)` : "Nothing to undo";
    redo.title = redoLabel ? `Redo: ${redoLabel} (Ctrl+Shift+Z)` : "Nothing to redo";
    conflict.hidden = state.kind !== "conflict";
    if (state.kind === "conflict") {
      conflictMessage.textContent = conflictText(state, unsaved);
      theirsList.replaceChildren(
        ...state.theirs.map((r) => el("li", { text: `#${r.number} by ${r.author}: ${r.summary}` })),
      );
    }
    error.hidden = state.kind !== "error";
    error.textContent = state.kind === "error" ? state.message : "";
    notice.hidden = !session.notice;
    notice.textContent = session.notice ?? "";
    const recovered = session.recovered;
    recovery.hidden = !recovered;
    restore.disabled = !editable;
    if (recovered) {
      const changes = [
        ...recovered.edits.map(describeEdit),
        ...(recovered.layout ? [LAYOUT_CHANGE] : []),
      ];
      recoveryText.textContent =
        `${plural(changes.length, "unsaved change")} from your last visit ` +
        `(${new Date(recovered.savedAt).toLocaleString()}, on revision ${recovered.baseRevision}) ` +
        `never reached the server: ${changes.join("; ")}.`;
    }
    pendingList.hidden = unsaved === 0;
    pendingItems.replaceChildren(
      ...pending.map((edit) =>
        el("li", { text: describeEdit(edit), attrs: { "data-child": edit.child } }),
      ),
      ...(session.layoutPending
        ? [el("li", { text: LAYOUT_CHANGE, attrs: { "data-layout": "" } })]
        : []),
    );
  };

  const scope = "Saving and history";
  const editable = () => session.editable;
  const inConflict = () => editable() && session.saveState.kind === "conflict";
  const removers = [
    registerShortcut({
      keys: ["Ctrl+Z"],
      description: "Undo the last edit (a support, a room corner or an object)",
      scope,
      enabled: editable,
      run: undoLast,
    }),
    registerShortcut({
      keys: ["Ctrl+Shift+Z", "Ctrl+Y"],
      description: "Redo",
      scope,
      enabled: editable,
      run: redoLast,
    }),
    registerShortcut({
      keys: "Ctrl+S",
      description: "Save now (edits are also saved after a short pause)",
      scope,
      enabled: editable,
      run: () => {
        if (!save.disabled) void session.save(author());
      },
    }),
    registerShortcut({
      keys: "Shift+M",
      description: "After a conflict: merge, saving your changes on top of theirs",
      scope,
      enabled: inConflict,
      run: () => void session.merge(author()),
    }),
    registerShortcut({
      keys: "Shift+R",
      description: "After a conflict: reload their version, yours re-applied unsaved",
      scope,
      enabled: inConflict,
      run: () => void session.reloadLatest({ hold: true }),
    }),
    registerShortcut({
      keys: "Shift+U",
      description: "Restore the changes your last visit left unsaved",
      scope,
      enabled: () => editable() && session.recovered !== null,
      run: () => session.restoreRecovered(),
    }),
  ];
  update();
  const unsubscribe = session.subscribe((change) => {
    if (change !== "hover" && change !== "select" && change !== "suggestions") update();
  });
  const unsubscribeObjects = objects?.subscribe(update);
  return () => {
    unsubscribe();
    unsubscribeObjects?.();
    for (const remove of removers) remove();
  };
}
