// The 3D panel's notice after object edits: the 3D scene was made by the last placement (or
// pipeline) run, so objects added, removed or changed since (class, box, mask) are not in it
// as they are now. The notice says which and offers "Re-place objects" (the layout editor's
// placement job, with its progress).
import "./placementNotice.css";
import type { SceneObject } from "@holiscene/schema";
import { button, el } from "../../dom";
import { replaceObjects } from "../../editors/replaceObjects";
import { plural, type SceneSession } from "../../state/sceneSession";
import { isStructural } from "../../state/supportGraph";
import { jobProgress } from "../common/jobProgress";

export interface PlacementChanges {
  added: string[];
  removed: string[];
  changed: string[];
}

/** What placement reads of an object (its 2D evidence). */
const placementInput = (o: SceneObject) => JSON.stringify([o.class, o.bbox, o.mask ?? null]);

/**
 * Whether `next` comes from a placement run after `previous`: an object of both has a new 3D
 * box (object edits never touch 3D boxes; an undone removal brings back the old one).
 */
export function newlyPlaced(previous: readonly SceneObject[], next: readonly SceneObject[]) {
  const before = new Map(previous.map((o) => [o.id, JSON.stringify(o.box_3d ?? null)]));
  return next.some((o) => {
    const old = before.get(o.id);
    return old !== undefined && o.box_3d != null && old !== JSON.stringify(o.box_3d);
  });
}

/**
 * The objects that differ between the ones the 3D scene was made from (`placed`) and the
 * current ones. An object a person added that has no 3D box yet counts as added even when
 * it was already there when the page opened (the notice comes back after a reload).
 */
export function changesSincePlacement(
  placed: readonly SceneObject[],
  current: readonly SceneObject[],
): PlacementChanges {
  const movable = (objects: readonly SceneObject[]) =>
    objects.filter((o) => !isStructural(o.class));
  const before = new Map(movable(placed).map((o) => [o.id, o]));
  const now = movable(current);
  const nowIds = new Set(now.map((o) => o.id));
  const added: string[] = [];
  const changed: string[] = [];
  for (const object of now) {
    const old = before.get(object.id);
    const unplaced = !object.box_3d && (object.set_by_person ?? []).includes("object");
    if (!old || unplaced) added.push(object.id);
    else if (placementInput(old) !== placementInput(object)) changed.push(object.id);
  }
  const removed = [...before.keys()].filter((id) => !nowIds.has(id));
  return { added, removed, changed };
}

export function describeChanges({ added, removed, changed }: PlacementChanges): string {
  const parts = [
    added.length > 0 && `${plural(added.length, "object")} added`,
    removed.length > 0 && `${removed.length} removed`,
    changed.length > 0 && `${changed.length} changed`,
  ].filter(Boolean);
  return parts.join(", ");
}

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

  // The objects the 3D scene shows were placed from: the loaded revision's, until a revision
  // with new 3D boxes (a placement or pipeline run) arrives.
  let placed = session.objects;
  let previous = session.objects;
  let running = false;
  let failure = "";

  const draw = () => {
    const hasRoom = session.doc.scene.layout?.corners_3d != null;
    const changes = changesSincePlacement(placed, session.objects);
    const summary = describeChanges(changes);
    notice.hidden = !hasRoom || (summary === "" && !running && failure === "");
    text.textContent = failure
      ? `Could not re-place the objects: ${failure}`
      : running
        ? "Placing the objects in the room again…"
        : `Objects changed since the 3D scene was made (${summary}):`;
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
        placed = session.objects;
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
      if (newlyPlaced(previous, session.objects)) placed = session.objects;
      previous = session.objects;
    }
    if (change === "document" || change === "lock") draw();
  });
  draw();
  return () => {
    abort.abort();
    unsubscribe();
    notice.remove();
  };
}
