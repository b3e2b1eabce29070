// A background job's progress (a pipeline run or a retrain): a bar, the stage and status.
import type { Job } from "@holiscene/schema";
import { el } from "../../dom";

/** The stage of a job `holiscene batch` made (the backend's store/jobs.py BATCH_STAGE): the
 * batch, not the server, runs it. */
const BATCH_STAGE = "batch";

/** What a scene page says while the job it waits for is unfinished. */
export function waitingText(job: Job): string {
  return job.stage === BATCH_STAGE
    ? "A batch (holiscene batch) is pre-annotating this scene; it opens when the batch has " +
        "done it. If that batch was stopped, the next batch takes the scene."
    : "The pipeline is still running on this scene; it opens when done.";
}

/** What each pipeline stage does, in an annotator's words (the stage names are the pipeline's:
 * `holiscene infer --stages`, docs/pipeline.md). */
const STAGE_WORDS: Record<string, string> = {
  objects_from_detections: "objects from the given boxes",
  objects_from_detector: "objects from the detector",
  intrinsics: "camera intrinsics",
  masks_grabcut: "masks",
  masks_from_boxes: "masks",
  layout_from_lines: "room layout",
  layout_from_depth: "room layout from the depth",
  layout_by_network: "room layout (network)",
  layout_from_revision: "room layout as saved",
  layout_holds_hung_objects: "walls moved to the objects",
  supports_from_network: "supports",
  supports_from_priors: "supports",
  heights_by_metrology: "object heights",
  placement: "3D placement",
  boxes_on_supporters: "3D placement",
  boxes_by_refiner: "3D boxes",
  boxes_by_network: "3D boxes (network)",
  boxes_from_depth: "3D boxes from the depth",
  shapes_fit: "shapes",
  shapes_by_mesh_net: "shapes (mesh network)",
  shape_completion: "shape completion",
  scene_mesh: "3D scene",
  scene_from_revision: "the saved scene",
};

/** A pipeline stage's name as people read it: "heights_by_metrology" -> "object heights"; a
 * stage without words of its own: "new_stage" -> "new stage". */
export function readableStage(name: string): string {
  return STAGE_WORDS[name] ?? name.replaceAll("_", " ");
}

/** A duration as people read it: "40 s", "7 min", "1 h 05 min". */
export function durationText(ms: number): string {
  const seconds = Math.max(0, Math.round(ms / 1000));
  if (seconds < 60) return `${seconds} s`;
  const minutes = Math.round(seconds / 60);
  if (minutes < 60) return `${minutes} min`;
  return `${Math.floor(minutes / 60)} h ${String(minutes % 60).padStart(2, "0")} min`;
}

/** How long a running job has run and, once it has gone far enough to tell, about how long it
 * has left at its pace so far (a retrain runs for minutes; its percentage alone said little). */
function timeText(job: Job, now: number): string {
  const elapsed = now - Date.parse(job.created_at);
  if (!(elapsed >= 5000)) return "";
  const left =
    job.progress >= 0.03 && elapsed >= 20_000
      ? `, about ${durationText((elapsed * (1 - job.progress)) / job.progress)} left`
      : "";
  return ` · ${durationText(elapsed)} so far${left}`;
}

/** What the job is doing; with `now` (ms), a running job's time so far and left. */
export function describeJob(job: Job, now?: number): string {
  const stage = job.stage ? readableStage(job.stage) : null;
  const percent = `${Math.round(job.progress * 100)}%`;
  const what = {
    retrain: "Retraining",
    detector_retrain: "Retraining",
    placement: "Placement",
    pipeline: "Pipeline",
  }[job.kind];
  const retraining = job.kind === "retrain" || job.kind === "detector_retrain";
  switch (job.status) {
    case "queued":
      return job.stage === BATCH_STAGE ? `${what} queued in a batch…` : `${what} queued…`;
    case "running":
      return (
        `Running${stage ? ` ${stage}` : ""} · ${percent}` +
        `${now === undefined ? "" : timeText(job, now)}${job.message ? ` · ${job.message}` : ""}`
      );
    case "succeeded":
      return retraining
        ? `Retraining finished: ${job.message ?? "done"}`
        : `${what} finished (revision ${job.result_revision ?? "?"})`;
    case "failed":
      return `${what} failed${stage ? ` in ${stage}` : ""}: ${job.error ?? "unknown error"}`;
    case "cancelled":
      // The message says it all ("cancelled by adam; no model was registered ...").
      return `${what} ${job.message ?? "cancelled"}`;
  }
}

/** A job in a table column, in a word or two; describeJob says it whole (the cell's title). */
export function jobColumnText(job: Job): string {
  switch (job.status) {
    case "queued":
      return job.stage === BATCH_STAGE ? "queued in a batch" : "queued";
    case "running":
      return `running ${Math.round(job.progress * 100)}%`;
    case "succeeded":
      return job.result_revision == null ? "done" : `done (revision ${job.result_revision})`;
    case "failed":
      return "failed";
    case "cancelled":
      return "cancelled";
  }
}

export interface JobProgress {
  element: HTMLElement;
  update(job: Job): void;
}

export function jobProgress(testid = "job-progress"): JobProgress {
  const bar = el("progress", { attrs: { max: 1, value: 0 } });
  const text = el("span", { className: "job-text" });
  const element = el(
    "div",
    { className: "job-progress", testid, attrs: { role: "status", "aria-live": "polite" } },
    bar,
    text,
  );
  return {
    element,
    update(job) {
      bar.value = job.status === "succeeded" ? 1 : job.progress;
      if (job.status === "queued") bar.removeAttribute("value");
      // A bar part filled beside "cancelled" or "failed" read as still going.
      bar.hidden = job.status === "cancelled" || job.status === "failed";
      text.textContent = describeJob(job, Date.now());
      element.dataset.status = job.status;
      element.classList.toggle("is-failed", job.status === "failed");
      element.classList.toggle("is-cancelled", job.status === "cancelled");
    },
  };
}
