// The 3D panel's notice after edits: the 3D scene was made by the last placement (or
// pipeline) run, so objects added, removed or changed since (class, box, mask), or a room
// layout set since, are not in it as they are now. The notice says what and offers
// "Re-place objects" (the layout editor's placement job, with its progress).
import "./placementNotice.css";
import { button, el } from "../../dom";
import { replaceObjects } from "../../editors/replaceObjects";
import type { SceneSession } from "../../state/sceneSession";
import { jobProgress } from "../common/jobProgress";
import { glbLacks, glbSourceRevision } from "../scene/glbStaleness";
import { changesSincePlacement, newlyPlaced } from "./placementChanges";

/** The notice, put in `panel` before `body`. Returns the function that removes it. */
export function mountPlacementNotice(
  panel: HTMLElement,
  body: HTMLElement,
  session: SceneSession,
): () => void {
  const abort = new AbortController();
  const text = el("span", { className: "placement-notice-text", testid: "placement-notice-text" });
  const replaceButton = button("Re-place objects", {
    className: "primary",
    testid: "placement-notice-replace",
    title: "Place the objects again in the room (a placement job)",
  });
  const progress = jobProgress("placement-notice-progress");
  progress.element.hidden = true;
  const notice = el(
    "div",
    {
      className: "alert alert--info placement-notice",
      testid: "placement-notice",
      attrs: { role: "status", hidden: true },
    },
    el("div", { className: "placement-notice-row" }, text, replaceButton),
    progress.element,
  );
  panel.insertBefore(notice, body);

  // The scene the 3D view was placed from: the revision that made the scene's scene.glb
  // (asked for below; the loaded revision until the answer), until a revision with new 3D
  // boxes (a placement or pipeline run) arrives.
  const loaded = session.doc.scene;
  let placed = loaded;
  // Whether `placed` is known to be a run's result (it tried every object it has).
  let placedByRun = false;
  const placedByARun = (scene: typeof loaded) => {
    placed = scene;
    placedByRun = true;
  };
  let previous = loaded.objects;
  let running = false;
  let failure = "";

  const draw = () => {
    const hasRoom = session.doc.scene.layout?.corners_3d != null;
    const changes = changesSincePlacement(placed.objects, session.objects, placedByRun);
    const summary = glbLacks(placed, session.doc.scene, placedByRun);
    notice.hidden = !hasRoom || (summary === "" && !running && failure === "");
    text.textContent = failure
      ? `Could not re-place the objects: ${failure}`
      : running
        ? "Placing the objects in the room again…"
        : `Changed since the 3D scene was made (${summary}):`;
    replaceButton.disabled = running || !session.editable;
    replaceButton.hidden = running || summary === "";
    notice.dataset.changed = [...changes.added, ...changes.changed, ...changes.removed].join(" ");
  };

  const run = async () => {
    running = true;
    failure = "";
    progress.element.hidden = false;
    draw();
    try {
      const job = await replaceObjects(session, {
        signal: abort.signal,
        onUpdate: progress.update,
      });
      if (job.status === "failed") failure = job.error ?? "the placement job failed";
      else {
        placedByARun(session.doc.scene);
        progress.element.hidden = true;
      }
    } catch (error) {
      if (abort.signal.aborted) return;
      failure = error instanceof Error ? error.message : String(error);
    }
    running = false;
    draw();
  };
  replaceButton.addEventListener("click", () => void run());

  const unsubscribe = session.subscribe((change) => {
    if (change === "document") {
      if (newlyPlaced(previous, session.objects)) placedByARun(session.doc.scene);
      previous = session.objects;
    }
    if (change === "document" || change === "lock") draw();
  });
  draw();
  glbSourceRevision(session.sceneId, session.doc, abort.signal)
    .then((made) => {
      // Not when a placement has run meanwhile: its objects are the 3D scene's now.
      if (made === null || placed !== loaded) return;
      placedByARun(made.scene);
      draw();
    })
    .catch(() => {}); // without the answer the notice counts from the loaded revision
  return () => {
    abort.abort();
    unsubscribe();
    notice.remove();
  };
}
