// Saving: status, Save / Discard, the list of unsaved edits, and the conflict message with
// its reload action. Unsaved edits stay listed until they are saved or discarded.
import { el } from "../dom";
import { setLeaveGuard } from "../router";
import { getAuthor } from "../state/author";
import { plural, type SaveState, type SceneSession } from "../state/sceneSession";
import { describeEdit } from "../state/supportGraph";

function statusText(state: SaveState, pending: number, revision: number): string {
  switch (state.kind) {
    case "clean":
      return `Revision ${revision} · no unsaved changes`;
    case "dirty":
      return `${plural(pending, "unsaved change")} on revision ${revision}`;
    case "saving":
      return "Saving…";
    case "saved":
      return `Saved as revision ${state.revision}`;
    case "conflict":
      return "Not saved: conflict";
    case "error":
      return "Not saved: error";
  }
}

function conflictText(state: Extract<SaveState, { kind: "conflict" }>, pending: number): string {
  const latest =
    state.currentRevision === null ? "" : ` (the latest is revision ${state.currentRevision})`;
  return (
    `Someone else saved this scene after you loaded revision ${state.baseRevision}${latest}. ` +
    `Your ${plural(pending, "change")} ${pending === 1 ? "was" : "were"} not saved and ` +
    `${pending === 1 ? "is" : "are"} kept below. Reload to see their changes with yours on top, then save again.`
  );
}

export function mountSaveBar(container: HTMLElement, session: SceneSession): () => void {
  const status = el("span", {
    className: "save-status",
    testid: "save-status",
    attrs: { role: "status", "aria-live": "polite" },
  });
  const save = el("button", {
    className: "primary",
    text: "Save",
    testid: "save-button",
    attrs: { type: "button", title: "Save (Ctrl+S)" },
    on: { click: () => void session.save(getAuthor()) },
  });
  const discard = el("button", {
    text: "Discard",
    testid: "discard-button",
    attrs: { type: "button" },
    on: { click: () => session.discard() },
  });
  const conflictMessage = el("p", { testid: "conflict-text" });
  const reload = el("button", {
    className: "primary",
    text: "Reload latest (keep my changes)",
    testid: "conflict-reload",
    attrs: { type: "button" },
    on: { click: () => void session.reloadLatest() },
  });
  const conflict = el(
    "div",
    { className: "alert alert--conflict", testid: "conflict-message", attrs: { role: "alert" } },
    el("strong", { text: "Conflict: your changes were not saved." }),
    conflictMessage,
    reload,
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
      discard,
      save,
    ),
    conflict,
    error,
    notice,
    pendingList,
  );

  const update = () => {
    const state = session.saveState;
    const pending = session.pending;
    status.textContent = statusText(state, pending.length, session.doc.revision);
    status.dataset.state = state.kind;
    container.dataset.state = state.kind;
    const busy = state.kind === "saving";
    save.disabled = busy || pending.length === 0 || state.kind === "conflict";
    discard.disabled = busy || pending.length === 0;
    conflict.hidden = state.kind !== "conflict";
    if (state.kind === "conflict")
      conflictMessage.textContent = conflictText(state, pending.length);
    error.hidden = state.kind !== "error";
    error.textContent = state.kind === "error" ? state.message : "";
    notice.hidden = !session.notice;
    notice.textContent = session.notice ?? "";
    pendingList.hidden = pending.length === 0;
    pendingItems.replaceChildren(
      ...pending.map((edit) =>
        el("li", { text: describeEdit(edit), attrs: { "data-child": edit.child } }),
      ),
    );
  };

  const onKey = (event: KeyboardEvent) => {
    if ((event.ctrlKey || event.metaKey) && event.key.toLowerCase() === "s") {
      event.preventDefault();
      if (!save.disabled) void session.save(getAuthor());
    }
  };
  // Leaving the page with unsaved edits asks first.
  const onBeforeUnload = (event: BeforeUnloadEvent) => {
    if (session.pending.length > 0) event.preventDefault();
  };
  window.addEventListener("keydown", onKey);
  window.addEventListener("beforeunload", onBeforeUnload);
  const removeLeaveGuard = setLeaveGuard(() => {
    const count = session.pending.length;
    return count > 0
      ? `Leave this scene? Your ${plural(count, "unsaved change")} will be lost.`
      : null;
  });
  update();
  const unsubscribe = session.subscribe((change) => {
    if (change !== "hover" && change !== "select") update();
  });
  return () => {
    unsubscribe();
    removeLeaveGuard();
    window.removeEventListener("keydown", onKey);
    window.removeEventListener("beforeunload", onBeforeUnload);
  };
}
