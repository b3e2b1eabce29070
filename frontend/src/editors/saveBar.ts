// Saving: status, Undo / Redo (of the last action: an unsaved support or layout edit, or a
// saved object action, see state/undoOrder.ts), Save / Discard, the list of unsaved edits, edits a previous
// visit left unsaved (restore or discard), and the conflict message with its merge and reload
// actions. Edits are autosaved (state/autosave.ts) and kept in localStorage until the server
// has them, so leaving the page needs no warning: nothing is lost.
import { button, el } from "../dom";
import { getAuthor } from "../state/author";
import type { ObjectEditor } from "../state/objectEditor";
import type { SceneSession } from "../state/sceneSession";
import { latestRedo, latestUndo } from "../state/undoOrder";
import { conflictPanel } from "./saving/conflictPanel";
import { pendingList } from "./saving/pendingList";
import { recoveryBanner } from "./saving/recoveryBanner";
import { saveKeys } from "./saving/saveKeys";
import { saveRow } from "./saving/saveRow";

// Its parts, in editors/saving/: the status and buttons (saveRow), the recovery banner, the
// conflict panel, the list of unsaved changes and the keys. Each updates itself from the
// session; this bar updates them all when the session or the object editor changes.

export function mountSaveBar(
  container: HTMLElement,
  session: SceneSession,
  objects: ObjectEditor | null = null,
): () => void {
  const author = () => getAuthor();
  const histories = objects ? [session, objects] : [session];
  const undoLast = () => void latestUndo(histories)?.undo();
  const redoLast = () => void latestRedo(histories)?.redo();
  const merge = () => void session.merge(author());
  const reload = () => void session.reloadLatest({ hold: true });

  const row = saveRow({
    session,
    histories,
    undoLast,
    redoLast,
    saveNow: () => void session.save(author()),
    objectAction: () => (objects?.status.kind === "busy" ? objects.status.label : null),
    objectFailed: () => objects?.failure?.label ?? null,
  });
  const recovery = recoveryBanner(session);
  const conflict = conflictPanel({ merge, reload });
  const error = el("div", {
    className: "alert alert--error",
    testid: "save-error",
    attrs: { role: "alert" },
  });
  const noticeText = el("span", { testid: "reload-notice-text" });
  const notice = el(
    "p",
    { className: "alert alert--info save-notice", testid: "reload-notice" },
    noticeText,
    button("×", {
      className: "link-button save-notice-close",
      testid: "reload-notice-close",
      title: "Dismiss this note",
      attrs: { "aria-label": "Dismiss this note" },
      onClick: () => session.dismissNotice(),
    }),
  );
  const pending = pendingList(session);
  container.replaceChildren(
    row.element,
    recovery.element,
    conflict.element,
    error,
    notice,
    pending.element,
  );

  const update = () => {
    const state = session.saveState;
    container.dataset.state = state.kind;
    row.update();
    conflict.update(state, session.unsavedCount);
    error.hidden = state.kind !== "error";
    error.textContent = state.kind === "error" ? state.message : "";
    notice.hidden = !session.notice;
    noticeText.textContent = session.notice ?? "";
    recovery.update();
    pending.update();
  };

  const removeKeys = saveKeys(session, {
    undoLast,
    redoLast,
    saveNow: () => {
      if (!row.save.disabled) void session.save(author());
    },
    merge,
    reload,
  });
  update();
  const unsubscribe = session.subscribe((change) => {
    if (change !== "hover" && change !== "select" && change !== "suggestions") update();
  });
  const unsubscribeObjects = objects?.subscribe(update);
  return () => {
    unsubscribe();
    unsubscribeObjects?.();
    removeKeys();
  };
}
