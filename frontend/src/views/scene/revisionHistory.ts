// The scene's revisions, newest first, refreshed whenever a new revision is loaded.
import { api } from "../../api/client";
import { el, formatTime } from "../../dom";
import type { SceneSession } from "../../state/sceneSession";

export function mountRevisionHistory(container: HTMLElement, session: SceneSession): () => void {
  const list = el("ol", { className: "revision-list", testid: "revision-list" });
  const details = el("details", { className: "history" }, el("summary", { text: "History" }), list);
  container.replaceChildren(details);
  let shownRevision = -1;
  const refresh = async () => {
    if (shownRevision === session.doc.revision) return;
    shownRevision = session.doc.revision;
    try {
      const revisions = await api.listRevisions(session.sceneId);
      list.replaceChildren(
        ...revisions
          .slice()
          .reverse()
          .map((r) =>
            el(
              "li",
              { attrs: { "data-revision": r.number } },
              el("strong", { text: `#${r.number}` }),
              ` ${r.kind} by ${r.author} · ${formatTime(r.created_at)} · ${r.summary}`,
            ),
          ),
      );
    } catch (error) {
      list.replaceChildren(el("li", { text: `Could not load the history: ${String(error)}` }));
    }
  };
  void refresh();
  return session.subscribe((change) => {
    if (change === "document") void refresh();
  });
}
