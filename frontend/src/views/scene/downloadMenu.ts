// The scene page's "Download" menu: the saved scene as scene.json, the 3D scene as scene.glb
// (once the pipeline made one) and the photo's objects as COCO JSON.
import { api } from "../../api/client";
import { downloadUrls, glbRevision } from "../../api/downloads";
import { el } from "../../dom";
import type { SceneSession } from "../../state/sceneSession";
import "./downloadMenu.css";
import { glbStaleness } from "./glbStaleness";

function item(testid: string, href: string, label: string, hint: string): HTMLAnchorElement {
  return el(
    "a",
    { className: "download-item", testid, attrs: { href, download: "", role: "menuitem" } },
    el("span", { className: "download-label", text: label }),
    el("span", { className: "download-hint", text: hint }),
  );
}

/**
 * `mayHaveGlb`: whether the revision shown can have a 3D scene; when it cannot, the menu says
 * so without asking the server (whose 404 the console would show as an error). `shown`: the
 * scene on the page: its revision, against which the 3D scene's age is told, and whether it
 * can be edited (what brings an old file up to date).
 */
export function downloadMenu(
  sceneId: string,
  mayHaveGlb: () => boolean,
  shown: () => Pick<SceneSession, "doc" | "editable"> | null,
): { element: HTMLElement; dispose: () => void } {
  const glb = item(
    "download-glb",
    downloadUrls.glb(sceneId),
    "3D scene (scene.glb)",
    "the placed objects and the room, for Blender or any glTF viewer",
  );
  const noGlb = el("p", {
    className: "download-none",
    testid: "download-no-glb",
    text: "3D scene (scene.glb): none yet; the pipeline makes it",
  });
  const glbHint = glb.querySelector(".download-hint") as HTMLElement;
  const freshHint = glbHint.textContent ?? "";
  glb.hidden = noGlb.hidden = true;
  const list = el(
    "div",
    { className: "download-list", attrs: { role: "menu" } },
    item(
      "download-scene-json",
      downloadUrls.sceneJson(sceneId),
      "Scene (scene.json)",
      "the saved revision: objects, supports, camera and room",
    ),
    glb,
    noGlb,
    item(
      "download-coco",
      downloadUrls.coco(sceneId),
      "Objects as COCO JSON",
      "boxes, NYU-40 classes and masks of the photo's objects",
    ),
  );
  const element = el(
    "details",
    { className: "download-menu", testid: "download-menu" },
    el("summary", { text: "Download", testid: "download-button" }),
    list,
  );
  let probe: AbortController | null = null;
  // Asked on every opening: a pipeline run or "Re-place objects" may have made one since.
  element.addEventListener("toggle", () => {
    // A check still running when the menu closes finishes unseen (aborting it left a
    // net::ERR_ABORTED in the console on every quick close); a new opening asks again.
    if (!element.open) return;
    probe?.abort();
    if (!mayHaveGlb()) {
      glb.hidden = true;
      noGlb.hidden = false;
      return;
    }
    probe = new AbortController();
    const signal = probe.signal;
    const page = shown();
    const current = page?.doc ?? null;
    glbRevision(sceneId, signal)
      .then(async (made) => {
        glb.hidden = made === null;
        noGlb.hidden = made !== null;
        glbHint.textContent = freshHint;
        glb.classList.remove("is-stale");
        if (made === null || current === null || !(made < current.revision)) return;
        const old = await api.getRevision(sceneId, made, signal);
        const stale = glbStaleness(old, current, page?.editable);
        if (stale) {
          glbHint.textContent = stale;
          glb.classList.add("is-stale");
        }
      })
      .catch(() => {
        if (!signal.aborted) glb.hidden = noGlb.hidden = true;
      });
  });
  list.addEventListener("click", (event) => {
    if ((event.target as Element).closest("a")) element.open = false;
  });
  element.addEventListener("keydown", (event) => {
    if (event.key === "Escape" && element.open) {
      event.stopPropagation(); // closes the menu, not the photo's tool
      element.open = false;
      element.querySelector("summary")?.focus();
    }
  });
  const closeOutside = (event: PointerEvent) => {
    if (element.open && !element.contains(event.target as Node)) element.open = false;
  };
  document.addEventListener("pointerdown", closeOutside);
  return {
    element,
    dispose: () => {
      probe?.abort();
      document.removeEventListener("pointerdown", closeOutside);
    },
  };
}
