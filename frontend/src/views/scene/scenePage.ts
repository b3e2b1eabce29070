// The scene page: waits for a running pipeline job, then shows the photo with overlays, the
// 3D scene and the support editor, all on one SceneSession (sceneWorkbench.ts).
import type { Job, SceneDocument, SceneSummary } from "@holiscene/schema";
import { api } from "../../api/client";
import { ApiError } from "../../api/errors";
import { isFinished, pollJob } from "../../api/jobs";
import { workflowApi } from "../../api/workflow";
import { button, el } from "../../dom";
import { warnBeforeLeaving } from "../../editors/saving/leaveWarning";
import { getAuthor } from "../../state/author";
import { titleUnlessLocked } from "../../state/editLock";
import { saveDone } from "../../state/savesInFlight";
import { SceneSession } from "../../state/sceneSession";
import { jobProgress, waitingText } from "../common/jobProgress";
import { mayHaveGlb } from "../scene3d/viewportObjects";
import { downloadMenu } from "./downloadMenu";
import { sceneMeta } from "./sceneMeta";
import { mountSceneWorkbench } from "./sceneWorkbench";
import { viserLink } from "./viserLink";

/** The scene's line of the scene list: its name and latest job (null when it is not there). */
async function sceneSummary(sceneId: string, signal: AbortSignal): Promise<SceneSummary | null> {
  const scenes = await workflowApi.listScenes(null, signal, false, "include");
  return scenes.find((s) => s.id === sceneId) ?? null;
}

const RERUN_TITLE = "Run the whole pipeline again on this photo; the labels people set are kept";

const rerunQuestion = (name: string) =>
  `Run the whole pipeline again on "${name}"? What it made (masks, supports, heights, 3D ` +
  "boxes, meshes) is made afresh; every label a person set is kept. The scene is read only " +
  "for everyone until the run ends.";

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
  let shown: SceneSession | null = null; // the scene on the page, once loaded
  const viser = viserLink(sceneId);
  const downloads = downloadMenu(
    sceneId,
    () => shown === null || mayHaveGlb(shown.doc),
    () => shown,
  );
  // Tab's first stop after the app's header, shown only while it has the focus: the scene's
  // header and the warnings' object links come before the photo otherwise (26 stops on t3d-1).
  const skip = button("Skip to the photo tools", {
    className: "skip-link",
    testid: "skip-to-photo",
    onClick: () => content.querySelector<HTMLElement>(".photo-tools button")?.focus(),
  });
  container.replaceChildren(
    el(
      "div",
      { className: "scene-page" },
      skip,
      el(
        "div",
        { className: "scene-header" },
        el("a", { className: "back", text: "← All scenes", attrs: { href: "#/" } }),
        title,
        meta,
        el("span", { className: "spacer" }),
        downloads.element,
        viser.element,
        rerun,
      ),
      viser.note,
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
    shown = session;
    title.textContent = doc.scene.name;
    title.title = doc.scene.name;
    document.title = `${doc.scene.name} · HoliScene`; // the tab names the scene, not its id
    const updateMeta = () => {
      const { text, title: note } = sceneMeta(session.doc);
      meta.textContent = text;
      meta.title = `${text}\n${note}`; // whole, where the header cuts it short
    };
    updateMeta();
    viser.showRevision(doc.revision);
    mountSceneWorkbench(content, session, disposers);
    disposers.push(warnBeforeLeaving(session));
    disposers.push(
      session.subscribe((change) => {
        if (change === "document") {
          updateMeta();
          viser.showRevision(session.doc.revision);
        }
        if (change === "lock") showRerun();
      }),
    );
    // Off on a read-only scene: the title says why (submitted, accepted, another's...).
    const showRerun = () => {
      rerun.disabled = !session.editable;
      rerun.title = titleUnlessLocked(RERUN_TITLE, session.lock);
    };
    showRerun();
    // The re-run keeps what people set, so unsaved edits are saved first, not dropped; if
    // they cannot be (a conflict, the server away), nothing runs and the save bar says why.
    rerun.onclick = async () => {
      // One click beside "Open in viser" must not start a run by mistake: it replaces what
      // the pipeline made and locks the scene for everyone until it ends.
      if (!window.confirm(rerunQuestion(session.doc.scene.name))) return;
      if (session.unsavedCount > 0 || session.saveState.kind === "saving") {
        rerun.disabled = true;
        await saveDone(session); // an autosave on its way
        if (session.unsavedCount > 0) await session.save(getAuthor());
        rerun.disabled = !session.editable;
        if (session.unsavedCount > 0) {
          message.replaceChildren(
            el("p", {
              className: "alert alert--error",
              testid: "rerun-refused",
              attrs: { role: "alert" },
              text:
                "The pipeline was not run: your unsaved changes could not be saved first " +
                "(the save bar under Support relations says why).",
            }),
          );
          return;
        }
      }
      message.replaceChildren();
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
    const summary = await sceneSummary(sceneId, abort.signal);
    if (summary) title.textContent = summary.name; // named while its pipeline job runs
    const job = summary?.latest_job ?? null;
    if (job && !isFinished(job)) {
      message.textContent = waitingText(job);
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
    // The scene stays in view, read only, while the pipeline runs again (the progress bar
    // names the stage); its result replaces it.
    shown?.setRerunning(true);
    try {
      await waitForJob(await api.startPipeline(sceneId));
      await load();
    } catch (error) {
      shown?.setRerunning(false);
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
    viser.dispose();
  };
}
