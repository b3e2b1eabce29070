// Room-layout editing: the bar above the photo that turns corner dragging on and off, says how
// the fit goes, saves the layout now (a SetLayout edit; the session also saves it by itself
// after a pause, with the support edits, and undoes a drag like any edit), and re-places the
// objects in the saved room (a placement job, with its progress).
import "./layoutEditor.css";
import type { Job } from "@holiscene/schema";
import { errorText } from "../api/errors";
import { isFinished } from "../api/jobs";
import { button, el } from "../dom";
import type { Point2 } from "../geometry/camera";
import { registerShortcut } from "../shortcuts";
import { getAuthor } from "../state/author";
import { titleUnlessLocked } from "../state/editLock";
import { LayoutDraft } from "../state/layoutDraft";
import type { SceneSession } from "../state/sceneSession";
import { jobProgress } from "../views/common/jobProgress";
import { frameFor } from "../views/photo/arrowGeometry";
import { drawingRect, insideRect } from "../views/photo/cornerHandles";
import { mountLayoutLayer } from "../views/photo/layoutLayer";
import { cameraHeightField } from "./layout/cameraHeightField";
import { layoutStatus, type StatusLine } from "./layout/layoutStatus";
import { replaceObjects } from "./replaceObjects";

export const LAYOUT_EDIT_KEY = "E";

/** What end-to-end tests read from the layout bar (its `layoutProbe` property). */
export interface LayoutProbe {
  /** Milliseconds of every room fit since the layout was last loaded or reset. */
  fitTimes(): number[];
  /** The room shown: its 8 corners and the camera's pitch and roll. */
  live(): { corners3d: number[][]; pitchDeg: number; rollDeg: number } | null;
  error(): string | null;
}

export type ProbedLayoutBar = HTMLElement & { layoutProbe?: LayoutProbe };

/**
 * Room-layout editing on a scene page: the draft, its bar (put before the photo) and its
 * handles on the photo. Mount after the photo view (the handles go into its SVG); the 3D view
 * takes the draft to follow the drags.
 */
export function mountLayoutEditing(
  photoPanel: HTMLElement,
  photoBody: HTMLElement,
  session: SceneSession,
): { draft: LayoutDraft; dispose: () => void } {
  const { width, height } = session.doc.scene.image;
  const frame = frameFor(width, height);
  // A corner is in view on the photo or in the margin around it (where handles can be grabbed).
  const drawing = drawingRect(frame);
  const inView = (point: Point2) => insideRect(point, drawing);
  const draft = new LayoutDraft(session.doc, inView);
  const detach = session.attachLayout(draft);
  const bar: ProbedLayoutBar = el("div");
  bar.layoutProbe = {
    fitTimes: () => [...draft.fitTimes],
    live: () => {
      const live = draft.live;
      return live && { corners3d: live.corners3d, pitchDeg: live.pitchDeg, rollDeg: live.rollDeg };
    },
    error: () => draft.error,
  };
  photoPanel.insertBefore(bar, photoBody);
  const disposers = [mountLayoutEditor(bar, session, draft), detach];
  const svg = photoBody.querySelector<SVGSVGElement>("svg[data-testid='photo']");
  if (svg) disposers.push(mountLayoutLayer(svg, frame, draft, () => session.doc.scene.camera));
  return {
    draft,
    dispose: () => {
      for (const dispose of disposers) dispose();
      bar.remove();
    },
  };
}

function mountLayoutEditor(
  bar: HTMLElement,
  session: SceneSession,
  draft: LayoutDraft,
): () => void {
  const abort = new AbortController();
  const toggle = button("Edit layout", {
    testid: "layout-toggle",
    title: `Drag the room's corners on the photo (${LAYOUT_EDIT_KEY})`,
    onClick: () => draft.setEditing(!draft.editing),
  });
  const save = button("Save layout", {
    testid: "layout-save",
    title: "Save the moved corners now (they are also saved by themselves after a pause)",
    onClick: () => void session.save(getAuthor()),
  });
  const reset = button("Reset", {
    testid: "layout-reset",
    title: "Back to the saved layout (Ctrl+Z undoes this)",
    onClick: () => draft.reset(),
  });
  const replace = button("Re-place objects", {
    testid: "replace-objects",
    title: "Place the objects again in the saved room (a placement job)",
    onClick: () => void replace3d(),
  });
  // What each button does; on a read-only scene, why it is off instead.
  const titles = new Map([toggle, save, reset, replace].map((b) => [b, b.title]));
  const heightField = cameraHeightField(draft, (problem) => {
    message = problem === null ? null : { text: problem, alert: true };
    draw();
  });
  const status = el("span", { className: "layout-status", testid: "layout-status" });
  const progress = jobProgress("placement-progress");
  progress.element.hidden = true;
  let job: Job | null = null;
  let message: StatusLine | null = null;

  bar.classList.add("layout-bar");
  bar.dataset.testid = "layout-bar";
  // The buttons keep their line; what editing adds (the camera's height, the room's figures)
  // comes on a line of its own below them, so the buttons do not move when editing starts.
  const details = el("div", { className: "layout-row" }, heightField.element, status);
  bar.replaceChildren(
    el(
      "div",
      { className: "layout-row" },
      toggle,
      el("span", { className: "spacer" }),
      reset,
      save,
      replace,
    ),
    details,
    progress.element,
  );

  const draw = () => {
    const running = job !== null && !isFinished(job);
    const saving = session.saveState.kind === "saving";
    const editable = session.editable;
    for (const [control, title] of titles) control.title = titleUnlessLocked(title, session.lock);
    toggle.disabled = !draft.available || !editable;
    toggle.setAttribute("aria-pressed", String(draft.editing));
    heightField.update(editable, saving, session.doc.scene.layout?.note);
    toggle.classList.toggle("is-active", draft.editing);
    save.disabled = !editable || saving || draft.edit() === null;
    reset.disabled = !editable || saving || !draft.dirty;
    // The placement job runs on the saved layout: save (or reset) the moved corners first.
    replace.disabled = !editable || running || saving || draft.dirty || !draft.hasStoredRoom;
    const { text, alert } = layoutStatus(draft, session.saveState, message);
    // While a corner is dragged the line keeps its height (a longer text is cut until the
    // drop): the photo under the pointer must not move.
    if (!draft.dragging) status.style.height = "";
    else if (!status.style.height)
      status.style.height = `${status.getBoundingClientRect().height}px`;
    status.classList.toggle("is-held", draft.dragging);
    status.textContent = text;
    details.hidden = heightField.element.hidden && text === "";
    status.classList.toggle("is-alert", alert);
    if (alert) status.setAttribute("role", "alert");
    else status.removeAttribute("role");
    bar.dataset.editing = String(draft.editing);
    bar.dataset.dirty = String(draft.dirty);
    bar.dataset.fitError = draft.error ?? "";
    const last = draft.fitTimes.at(-1);
    if (last !== undefined) bar.dataset.fitMs = last.toFixed(3);
  };

  const replace3d = async () => {
    message = null;
    progress.element.hidden = false;
    try {
      job = await replaceObjects(session, {
        signal: abort.signal,
        onUpdate: (update) => {
          const first = job === null || job.id !== update.id;
          job = update;
          progress.update(update);
          if (first) draw();
        },
      });
    } catch (error) {
      if (abort.signal.aborted) return;
      message = { text: `Could not re-place the objects: ${errorText(error)}`, alert: true };
    }
    draw();
  };

  const removeKey = registerShortcut({
    keys: LAYOUT_EDIT_KEY,
    description: "Edit the room layout (drag its corners on the photo), or stop",
    scope: "Room layout",
    run: () => draft.setEditing(!draft.editing),
    enabled: () => draft.available && session.editable,
  });
  const unsubscribeDraft = draft.subscribe((change) => {
    if (change === "saved") {
      // The objects keep their places until they are placed again in the new room.
      const text = `Layout saved (revision ${session.doc.revision}). "Re-place objects" moves the objects into it.`;
      message = { text, alert: false };
    } else if (change !== "fit" || draft.dirty) message = null;
    draw();
  });
  const unsubscribeSession = session.subscribe((change) => {
    if (change === "save" || change === "lock" || change === "document") draw();
  });
  draw();
  return () => {
    abort.abort();
    removeKey();
    unsubscribeDraft();
    unsubscribeSession();
  };
}
