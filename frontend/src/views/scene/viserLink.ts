// "Open in viser": asks the server for the scene's viser viewer (started on demand on
// 127.0.0.1, one per scene, POST /api/scenes/{id}/viewer) and opens it in a new tab. Once
// opened, the viewer follows the page: a newer revision asks the server again, which rebuilds
// the running viewer in place (its open tab redraws without a reload).
import { api } from "../../api/client";
import { button, el } from "../../dom";

export interface ViserLink {
  element: HTMLElement;
  /** How to reach the viewer from another machine, for under the header (hidden when the
   * page is on the server itself). */
  note: HTMLElement;
  /** The scene's revision on the page: a viewer of an older one says it is behind. */
  showRevision(revision: number): void;
  /** The page is left: a rebuild waiting for the saves to pause is not asked for. */
  dispose(): void;
}

const VIEWER_FOLLOW_MS = 2000;

const LOOPBACK = new Set(["localhost", "127.0.0.1", "[::1]", "::1"]);

/** The viewer listens on the server's loopback only (viser has no login): from another
 * machine its address is the reviewer's own loopback, so the page says how to reach it. */
export function remoteViewerNote(url: string, pageHost: string): string | null {
  if (LOOPBACK.has(pageHost)) return null;
  const port = new URL(url).port;
  return (
    `The viewer runs on the server and answers there only (it has no login). From this ` +
    `machine, forward its port first: ssh -L ${port}:127.0.0.1:${port} ${pageHost}, ` +
    `then open ${url}.`
  );
}

/** A button that opens the viewer, and a link to it once it runs. */
export function viserLink(sceneId: string): ViserLink {
  let opened: number | null = null; // the revision the running viewer shows
  let latest = 0;
  let followTimer: ReturnType<typeof setTimeout> | undefined;
  const link = el("a", {
    testid: "viser-link",
    attrs: { target: "_blank", rel: "noopener", hidden: true },
  });
  const note = el("span", {
    className: "alert alert--info viser-remote-note",
    testid: "viser-remote-note",
    attrs: { hidden: true },
  });
  const openButton = button("Open in viser", {
    testid: "open-viser",
    title: "The 3D review viewer (viser), in a new tab",
  });
  // Saves come in bursts while someone edits: rebuild once they pause.
  const follow = () => {
    clearTimeout(followTimer);
    followTimer = setTimeout(async () => {
      if (opened === null || latest <= opened) return;
      try {
        opened = (await api.openViewer(sceneId)).revision;
      } catch {
        // The link keeps saying the viewer is behind; "Open in viser" tries again.
      }
      showLinkText();
    }, VIEWER_FOLLOW_MS);
  };
  openButton.onclick = async () => {
    // Open the tab now, while the click still counts as the user's: popup blockers refuse
    // a window opened after an await.
    const remote = !LOOPBACK.has(window.location.hostname);
    const tab = remote ? null : window.open("about:blank", "_blank");
    if (tab) tab.opener = null;
    openButton.disabled = true;
    try {
      const info = await api.openViewer(sceneId);
      link.href = info.url;
      opened = info.revision;
      showLinkText();
      link.title = `${info.url} — from a shell: ${info.command}`;
      link.hidden = false;
      if (tab) tab.location.href = info.url;
      note.textContent = remoteViewerNote(info.url, window.location.hostname) ?? "";
      note.hidden = note.textContent === "";
    } catch (error) {
      tab?.close();
      link.removeAttribute("href");
      link.textContent = `No viewer: ${error instanceof Error ? error.message : String(error)}`;
      link.hidden = false;
    } finally {
      openButton.disabled = false;
    }
  };
  function showLinkText(): void {
    if (opened === null) return;
    link.textContent =
      latest > opened
        ? `viewer of revision ${opened} (now ${latest}: open again)`
        : `viewer of revision ${opened}`;
  }
  return {
    element: el("span", { className: "viser-link" }, openButton, " ", link),
    note,
    showRevision(revision) {
      latest = revision;
      showLinkText();
      if (opened !== null && latest > opened) follow();
    },
    dispose() {
      clearTimeout(followTimer);
      opened = null;
    },
  };
}
