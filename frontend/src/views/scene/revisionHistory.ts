// The scene's revisions, newest first, refreshed whenever a new revision is loaded. Each one
// can show what it changed (diff against the revision before it) and be reverted to: the whole
// scene goes back exactly as that revision stored it (a new revision; undo takes it back).

import type { RevisionInfo, SceneDocument } from "@holiscene/schema";
import { deferred } from "../../afterPaint";
import { api } from "../../api/client";
import { errorText } from "../../api/errors";
import { button, el, formatTime } from "../../dom";
import { registerShortcut } from "../../shortcuts";
import { titleUnlessLocked } from "../../state/editLock";
import type { ObjectEditor } from "../../state/objectEditor";
import type { SceneSession } from "../../state/sceneSession";
import { diffLines } from "./history/diffLines";
import { revertTo } from "./history/revertRevision";
import { revisionSummary } from "./history/revisionSummary";
import { linkObjectIds } from "./objectIdLinks";

export interface RevisionHistory {
  /** Open the history at what changed from revision `from` to the current one. */
  showSince(from: number): void;
  dispose(): void;
}

export function mountRevisionHistory(
  container: HTMLElement,
  session: SceneSession,
  editor: ObjectEditor,
): RevisionHistory {
  const list = el("ol", { className: "revision-list", testid: "revision-list" });
  const summary = el("summary", { text: "History", testid: "history-toggle" });
  // Why a revert did nothing, beside the button clicked; gone with the next revision.
  const note = el("p", {
    className: "alert alert--info history-note",
    testid: "history-note",
    attrs: { role: "status" },
  });
  const details = el("details", { className: "history", testid: "history" }, summary, note, list);
  container.replaceChildren(details);
  const documents = new Map<number, Promise<SceneDocument>>(); // revisions never change
  const revision = (n: number) => {
    let doc = documents.get(n);
    if (!doc) {
      doc = api.getRevision(session.sceneId, n);
      documents.set(n, doc);
      doc.catch(() => documents.delete(n));
    }
    return doc;
  };

  /** Show (or hide) in `box` what changed from revision `from` (null: none) to `to`; `mode`
   * says which question the box answers, so the other button asks again. */
  const showDiff = async (
    box: HTMLElement,
    mode: string,
    from: number | null,
    to: () => Promise<SceneDocument>,
  ) => {
    if (!box.hidden && box.dataset.mode === mode) {
      box.hidden = true;
      return;
    }
    box.hidden = false;
    box.dataset.mode = mode;
    box.replaceChildren(el("li", { text: "Loading…" }));
    try {
      const after = await to();
      const before = from !== null && from >= 1 ? await revision(from) : null;
      const idsNow = new Set(session.objects.map((o) => o.id));
      // Each object a line names is a link that selects it on the photo, as in the warnings.
      const linkIds = (text: string) =>
        linkObjectIds(
          text,
          idsNow,
          (id) => session.select(id),
          (id) => `${id} is not in the scene now`,
        );
      const lines = diffLines(
        before,
        after,
        (id) => (before !== null ? restoreLink(id, before.revision) : null),
        linkIds,
      );
      const none = mode === "since" && lines.length === 0;
      box.replaceChildren(...(none ? [el("li", { text: "nothing has changed since" })] : lines));
    } catch (error) {
      box.replaceChildren(el("li", { text: `Could not load the diff: ${String(error)}` }));
    }
  };

  /** Show (or hide) in `box` what changed from revision `from` to the current one. */
  const showChangesSince = (box: HTMLElement, from: number) =>
    showDiff(box, "since", from, async () => session.doc);

  /** One removed object back as revision `from` had it (restore_object: one new revision,
   * undoable), without reverting everything else that changed since. */
  const restoreLink = (id: string, from: number): HTMLElement | null => {
    if (session.object(id)) return null; // back in the scene already
    const link = button("restore", {
      className: "link-button",
      testid: `restore-object-${id}`,
      title: `Bring ${id} back as revision ${from} had it; nothing else changes`,
      disabled: !session.editable,
    });
    link.onclick = async () => {
      link.disabled = true;
      note.textContent = "";
      try {
        editor.remember(await revision(from)); // shown at once, before the server answers
        await editor.apply([{ kind: "restore_object", id, from_revision: from }], `restore ${id}`);
      } catch (error) {
        note.textContent = `Could not restore ${id}: ${errorText(error)}`;
        link.disabled = false;
      }
    };
    return link;
  };

  const revert = async (info: RevisionInfo, revertButton: HTMLButtonElement) => {
    revertButton.disabled = true;
    note.textContent = "";
    try {
      note.textContent = (await revertTo(editor, info.number, await revision(info.number))) ?? "";
      // The note heads the list; the button clicked may be far down it.
      if (note.textContent) note.scrollIntoView({ block: "nearest" });
    } catch (error) {
      note.textContent = `Could not revert: ${errorText(error)}`;
      note.scrollIntoView({ block: "nearest" });
    } finally {
      revertButton.disabled = false;
    }
  };

  const item = (info: RevisionInfo, current: number) => {
    const diff = el("ul", {
      className: "revision-diff",
      testid: `revision-diff-${info.number}`,
      attrs: { hidden: true },
    });
    const showButton = button("Diff", {
      className: "link-button",
      testid: `revision-diff-button-${info.number}`,
      title: "What this revision changed",
      onClick: () => void showDiff(diff, "own", info.number - 1, () => revision(info.number)),
    });
    // A reviewer checks what changed since the revision they sent back, in one list.
    const sinceButton = button("Since", {
      className: "link-button",
      testid: `revision-since-button-${info.number}`,
      title: "What changed from this revision to the current one",
      onClick: () => void showChangesSince(diff, info.number),
    });
    const revertButton = button("Revert to this", {
      className: "link-button",
      testid: `revision-revert-${info.number}`,
      // Off on a read-only scene: the title says why.
      title: titleUnlessLocked(
        "Put the whole scene back as it was in this revision (objects, supports, room)",
        session.lock,
      ),
    });
    revertButton.onclick = () => void revert(info, revertButton);
    const summary = revisionSummary(info.summary);
    revertButton.disabled = !session.editable;
    return el(
      "li",
      { attrs: { "data-revision": info.number } },
      el("strong", { text: `#${info.number}` }),
      ` ${info.kind} by ${info.author} · ${formatTime(info.created_at)} · `,
      el("span", { text: summary.text, attrs: summary.title ? { title: summary.title } : {} }),
      " ",
      showButton,
      ...(info.number < current
        ? [" ", sinceButton, " ", revertButton]
        : [el("span", { className: "badge", text: "current" })]),
      diff,
    );
  };

  let shownRevision = -1;
  let listed: Promise<void> = Promise.resolve();
  const refresh = () => {
    if (shownRevision === session.doc.revision) return listed;
    shownRevision = session.doc.revision;
    listed = fill();
    return listed;
  };
  const fill = async () => {
    try {
      const revisions = await api.listRevisions(session.sceneId);
      const current = session.doc.revision;
      list.replaceChildren(
        ...revisions
          .slice()
          .reverse()
          .map((r) => item(r, current)),
      );
    } catch (error) {
      list.replaceChildren(el("li", { text: `Could not load the history: ${String(error)}` }));
    }
  };
  void refresh();
  const removeKey = registerShortcut({
    keys: "Shift+H",
    description: "Open or close the revision history (diff, revert)",
    scope: "Saving and history",
    run: () => {
      details.open = !details.open;
      if (details.open) {
        details.scrollIntoView({ block: "nearest" });
        summary.focus({ preventScroll: true });
      }
    },
  });
  // After the new revision is drawn: the list is below the photo, and its request can wait.
  const refreshLater = deferred(() => void refresh());
  const unsubscribe = session.subscribe((change) => {
    if (change === "document") {
      note.textContent = "";
      refreshLater();
    }
    if (change === "lock") {
      for (const revertButton of list.querySelectorAll<HTMLButtonElement>(
        "[data-testid^='revision-revert-']",
      ))
        revertButton.disabled = !session.editable;
    }
  });
  const showSince = async (from: number) => {
    details.open = true;
    await refresh();
    const diff = list.querySelector<HTMLElement>(`[data-testid="revision-diff-${from}"]`);
    if (!diff) return;
    diff.closest("li")?.scrollIntoView({ block: "start" });
    if (diff.hidden || diff.dataset.mode !== "since") await showChangesSince(diff, from);
  };
  return {
    showSince: (from) => void showSince(from),
    dispose: () => {
      refreshLater.cancel();
      unsubscribe();
      removeKey();
    },
  };
}
