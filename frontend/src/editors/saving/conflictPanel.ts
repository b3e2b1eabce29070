// The save bar's conflict message: someone else saved the scene after it was loaded. Lists
// their revisions and offers to merge (save mine on top) or reload (theirs, mine re-applied).
import { button, el } from "../../dom";
import { getAuthor } from "../../state/author";
import { plural, type SaveState } from "../../state/sceneSession";

type Conflict = Extract<SaveState, { kind: "conflict" }>;

/** `me`: the author this page saves as (their own revisions in another tab are named so). */
export function conflictText(state: Conflict, pending: number, me = getAuthor()): string {
  const latest =
    state.currentRevision === null ? "" : ` (the latest is revision ${state.currentRevision})`;
  // The same person in another tab or window is told so: their own name read as a stranger's.
  const authors = [...new Set(state.theirs.map((r) => r.author))].map((author) =>
    author === me ? "You (in another tab or window)" : author,
  );
  const who = authors.join(", ") || "Someone else";
  return (
    `${who} saved this scene after you loaded revision ${state.baseRevision}${latest}. ` +
    `Your ${plural(pending, "change")} ${pending === 1 ? "was" : "were"} not saved and ` +
    `${pending === 1 ? "is" : "are"} kept (listed below, and in this browser). Merge to save ` +
    `yours on top of theirs, or reload to look at theirs first with yours re-applied unsaved.`
  );
}

export interface ConflictPanel {
  element: HTMLElement;
  /** Shown while the state is a conflict; `unsaved`: the changes kept. */
  update(state: SaveState, unsaved: number): void;
}

export function conflictPanel(actions: { merge(): void; reload(): void }): ConflictPanel {
  const message = el("p", { testid: "conflict-text" });
  const theirsList = el("ul", { className: "conflict-theirs", testid: "conflict-theirs" });
  const merge = button("Merge: save mine on top (Shift+M)", {
    className: "primary",
    testid: "conflict-merge",
    onClick: actions.merge,
  });
  const reload = button("Reload: review first (Shift+R)", {
    testid: "conflict-reload",
    onClick: actions.reload,
  });
  const element = el(
    "div",
    { className: "alert alert--conflict", testid: "conflict-message", attrs: { role: "alert" } },
    el("strong", { text: "Conflict: your changes were not saved." }),
    message,
    theirsList,
    el("div", { className: "save-row" }, merge, reload),
  );
  return {
    element,
    update(state, unsaved) {
      element.hidden = state.kind !== "conflict";
      if (state.kind !== "conflict") return;
      message.textContent = conflictText(state, unsaved);
      theirsList.replaceChildren(
        ...state.theirs.map((r) => el("li", { text: `#${r.number} by ${r.author}: ${r.summary}` })),
      );
    },
  };
}
