// The scene page: waits for a running pipeline job, then shows the photo with overlays, the
// 3D scene and the support editor, all on one SceneSession.
import type { Camera, Job, SceneDocument } from "@holiscene/schema";
import { api } from "../../api/client";
import { ApiError } from "../../api/errors";
import { isFinished, pollJob } from "../../api/jobs";
import { button, el } from "../../dom";
import { mountBoxTool } from "../../editors/boxTool";
import { mountEdgeInfo } from "../../editors/edgeInfo";
import { mountLayoutEditing } from "../../editors/layoutEditor";
import { mountMaskTools } from "../../editors/maskTools";
import { mountObjectShortcuts } from "../../editors/objectShortcuts";
import { mountSaveBar } from "../../editors/saveBar";
import { mountSupportEditor } from "../../editors/supportEditor";
import { mountSupportShortcuts } from "../../editors/supportShortcuts";
import { mountSupportSuggestions } from "../../inference/supportSuggestions";
import { getAuthor } from "../../state/author";
import { startAutosave } from "../../state/autosave";
import { ObjectEditor } from "../../state/objectEditor";
import { plural, SceneSession } from "../../state/sceneSession";
import { jobProgress } from "../common/jobProgress";
import { mountPhotoView } from "../photo/photoView";
import { mountPlacementNotice } from "../scene3d/placementNotice";
import { mountScene3d } from "../scene3d/scene3dView";
import { mountWorkflowBar } from "../workflow/workflowBar";
import { downloadMenu } from "./downloadMenu";
import { mountObjectSuggestions } from "./objectSuggestions";
import { pipelineWarningsPanel } from "./pipelineWarnings";
import { mountRevisionHistory } from "./revisionHistory";
import { viserLink } from "./viserLink";

function panel(title: string, className: string, testid: string) {
  const body = el("div", { className: "panel-body" });
  const element = el(
    "section",
    { className: `panel ${className}`, testid, attrs: { "aria-label": title } },
    el("h2", { text: title }),
    body,
  );
  return { element, body };
}

/** The scene's latest pipeline job, from the scene list (null when there is none). */
async function latestJob(sceneId: string, signal: AbortSignal): Promise<Job | null> {
  const scenes = await api.listScenes(signal);
  return scenes.find((s) => s.id === sceneId)?.latest_job ?? null;
}

/** The server's reason as a sentence: capital first, one full stop. */
const sentence = (text: string) =>
  `${text.charAt(0).toUpperCase()}${text.slice(1).replace(/\.?\s*$/, ".")}`;

/**
 * The banner of a scene that cannot be edited now (submitted, accepted, or the server said
 * so): why, what is off, and that unsaved changes are kept.
 */
function readOnlyBanner(session: SceneSession): { element: HTMLElement; dispose: () => void } {
  const reason = el("strong", { testid: "read-only-reason" });
  const detail = el("span", { testid: "read-only-detail" });
  const element = el(
    "div",
    {
      className: "alert alert--info read-only-banner",
      testid: "read-only-banner",
      attrs: { role: "status", hidden: true },
    },
    reason,
    " ",
    detail,
  );
  const update = () => {
    const lock = session.lock;
    element.hidden = lock === null;
    reason.textContent = lock?.title ?? "";
    const kept = session.unsavedCount;
    detail.textContent =
      (lock?.reason ? `${sentence(lock.reason)} ` : "") +
      "The support editor, the layout editor and their keys are off; the photo, the 3D view " +
      "and ? (the key list) still work." +
      (kept > 0
        ? ` Your ${plural(kept, "unsaved change")} ${kept === 1 ? "is" : "are"} kept in this browser until the scene can be edited again.`
        : "");
  };
  update();
  return {
    element,
    dispose: session.subscribe((change) => {
      if (change === "lock" || change === "edits" || change === "document") update();
    }),
  };
}

/** How the camera's height was found, in words. */
const HEIGHT_SOURCES: Record<NonNullable<Camera["height_source"]>, string> = {
  prior: "a prior",
  estimated: "estimated",
  manual: "set by hand",
  ground_truth: "ground truth",
};

export function mountScenePage(container: HTMLElement, sceneId: string): () => void {
  const abort = new AbortController();
  const disposers: (() => void)[] = [];
  const title = el("h1", { text: sceneId, testid: "scene-title" });
  const meta = el("span", { className: "scene-meta", testid: "scene-meta" });
  const progress = jobProgress("job-progress");
  progress.element.hidden = true;
  const message = el("div", { className: "page-message", testid: "scene-message" });
  const rerun = button("Run pipeline again", { testid: "run-pipeline", disabled: true });
  const content = el("div", { className: "scene-grid" });
  const downloads = downloadMenu(sceneId);
  container.replaceChildren(
    el(
      "div",
      { className: "scene-page" },
      el(
        "div",
        { className: "scene-header" },
        el("a", { className: "back", text: "← All scenes", attrs: { href: "#/" } }),
        title,
        meta,
        el("span", { className: "spacer" }),
        downloads.element,
        viserLink(sceneId),
        rerun,
      ),
      progress.element,
      message,
      content,
    ),
  );

  const disposeContent = () => {
    for (const dispose of disposers.splice(0)) dispose();
    content.replaceChildren();
  };

  const showScene = (doc: SceneDocument) => {
    disposeContent();
    const session = new SceneSession(doc);
    title.textContent = doc.scene.name;
    const updateMeta = () => {
      const { image, camera, layout } = session.doc.scene;
      const parts = [`${image.width}×${image.height}`, `revision ${session.doc.revision}`];
      // The scale of the whole scene, and where it came from (the layout's note says more).
      if (camera?.height_m != null) {
        const source = HEIGHT_SOURCES[camera.height_source ?? "estimated"];
        parts.push(`camera ${camera.height_m.toFixed(2)} m high (${source})`);
      }
      meta.textContent = parts.join(" · ");
      meta.title = layout?.note ?? "";
    };
    updateMeta();
    const photo = panel("Photo", "panel--photo", "photo-panel");
    const scene3d = panel("3D scene", "panel--scene3d", "scene3d-panel");
    const editor = panel("Support relations", "panel--editor", "editor-panel");
    const saveBar = el("div", { className: "save-bar", testid: "save-bar" });
    const table = el("div", { className: "editor-table" });
    const suggestions = el("div");
    const history = el("div");
    const workflow = el("div");
    editor.body.append(workflow, saveBar, suggestions, table, history);
    const edgeInfo = el("div");
    photo.element.append(edgeInfo);
    const banner = readOnlyBanner(session);
    const warnings = pipelineWarningsPanel(session);
    content.append(
      banner.element,
      warnings.element,
      el("div", { className: "scene-main" }, photo.element, scene3d.element),
      editor.element,
    );
    const objectEditor = new ObjectEditor(session);
    const photoView = mountPhotoView(photo.body, session, objectEditor);
    disposers.push(
      photoView.dispose,
      // after the photo view: it draws in its SVG
      mountObjectSuggestions(photo.body, session, objectEditor),
    );
    const layout = mountLayoutEditing(photo.element, photo.body, session);
    disposers.push(
      layout.dispose,
      mountEdgeInfo(edgeInfo, session),
      mountSupportShortcuts(session),
      mountBoxTool(photoView.tools),
      mountObjectShortcuts(objectEditor, photoView.tools.host.svg),
      // after the support keys: the polygon's Backspace wins while a polygon is drawn
      mountMaskTools(photoView.tools),
      startAutosave(session, { author: getAuthor, otherSaving: () => objectEditor.busy }),
      mountScene3d(scene3d.body, session, layout.draft),
      mountPlacementNotice(scene3d.element, scene3d.body, session),
      mountSaveBar(saveBar, session, objectEditor),
      mountSupportEditor(table, session),
      mountSupportSuggestions(suggestions, table, session),
      mountRevisionHistory(history, session),
      mountWorkflowBar(workflow, session),
      banner.dispose,
      warnings.dispose,
      session.subscribe((change) => {
        if (change === "document") updateMeta();
        if (change === "lock") rerun.disabled = !session.editable;
      }),
    );
    rerun.disabled = !session.editable;
    rerun.onclick = () => {
      const unsaved = session.unsavedCount;
      if (unsaved > 0 && !window.confirm(`Discard ${unsaved} unsaved change(s) and re-run?`))
        return;
      void runPipeline();
    };
  };

  const waitForJob = async (job: Job) => {
    progress.element.hidden = false;
    const finished = await pollJob(job, { signal: abort.signal, onUpdate: progress.update });
    progress.element.hidden = finished.status === "succeeded";
    return finished;
  };

  const load = async () => {
    rerun.disabled = true;
    message.textContent = "Loading…";
    const job = await latestJob(sceneId, abort.signal);
    if (job && !isFinished(job)) {
      message.textContent = "The pipeline is still running on this scene; it opens when done.";
      await waitForJob(job);
    } else if (job?.status === "failed") {
      progress.update(job);
      progress.element.hidden = false;
    }
    const doc = await api.getScene(sceneId, abort.signal);
    message.textContent = "";
    rerun.disabled = false;
    showScene(doc);
  };

  const runPipeline = async () => {
    rerun.disabled = true;
    try {
      disposeContent();
      message.textContent = "Running the pipeline…";
      await waitForJob(await api.startPipeline(sceneId));
      await load();
    } catch (error) {
      fail(error);
    }
  };

  const fail = (error: unknown) => {
    if (abort.signal.aborted) return;
    rerun.disabled = false;
    message.replaceChildren(
      el("p", {
        className: "alert alert--error",
        attrs: { role: "alert" },
        text:
          error instanceof ApiError && error.status === 404
            ? `There is no scene "${sceneId}".`
            : `Could not load the scene: ${error instanceof Error ? error.message : String(error)}`,
      }),
    );
  };

  load().catch(fail);
  return () => {
    abort.abort();
    disposeContent();
    downloads.dispose();
  };
}
