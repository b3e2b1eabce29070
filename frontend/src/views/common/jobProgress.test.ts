// A job's text on the scene page: a batch's job says the batch has the scene, not that the
// pipeline is running (nothing runs it until a batch does).
import type { Job } from "@holiscene/schema";
import { describe, expect, it } from "vitest";
import { describeJob, durationText, jobColumnText, waitingText } from "./jobProgress";

const job = (stage: string | null): Job => ({
  id: "j1",
  kind: "pipeline",
  status: "queued",
  stage,
  progress: 0,
  message: null,
  error: null,
  log: "",
  scene_id: "s1",
  base_revision: 1,
  result_revision: null,
  result_model_id: null,
  started_by: null,
  created_at: "2026-12-05T00:00:00Z",
  finished_at: null,
});

describe("job texts", () => {
  it("says a batch has the scene when the job is a batch's", () => {
    expect(waitingText(job("batch"))).toContain("holiscene batch");
    expect(describeJob(job("batch"))).toBe("Pipeline queued in a batch…");
  });

  it("says the pipeline runs for a server's job", () => {
    expect(waitingText(job(null))).toContain("still running");
    expect(describeJob(job(null))).toBe("Pipeline queued…");
  });

  it("names a running or failed job's stage as people read it", () => {
    const running: Job = { ...job("layout_from_lines"), status: "running", progress: 0.42 };
    expect(describeJob(running)).toBe("Running room layout · 42%");
    const failed: Job = { ...job("masks_grabcut"), status: "failed", error: "no memory" };
    expect(describeJob(failed)).toBe("Pipeline failed in masks: no memory");
    // A stage without words of its own is still read without its underscores.
    const other: Job = { ...job("some_new_stage"), status: "running", progress: 0.1 };
    expect(describeJob(other)).toBe("Running some new stage · 10%");
  });

  it("says how long a running job has run and, at its pace, about how long it has left", () => {
    const start = Date.parse("2026-12-05T00:00:00Z");
    const training: Job = {
      ...job("training"),
      kind: "retrain",
      status: "running",
      progress: 0.07,
    };
    expect(describeJob(training, start + 3000)).toBe("Running training · 7%");
    expect(describeJob(training, start + 12_000)).toBe("Running training · 7% · 12 s so far");
    expect(describeJob(training, start + 60_000)).toBe(
      "Running training · 7% · 1 min so far, about 13 min left",
    );
    const slow = { ...training, progress: 0.5 };
    expect(describeJob(slow, start + 3_600_000)).toBe(
      "Running training · 50% · 1 h 00 min so far, about 1 h 00 min left",
    );
    expect(durationText(89_000)).toBe("1 min");
  });

  it("says a job in a word or two for the scene list's column", () => {
    expect(jobColumnText(job(null))).toBe("queued");
    expect(jobColumnText({ ...job("masks"), status: "running", progress: 0.4 })).toBe(
      "running 40%",
    );
    const done: Job = { ...job(null), status: "succeeded", result_revision: 2 };
    expect(jobColumnText(done)).toBe("done (revision 2)");
    expect(jobColumnText({ ...job(null), status: "failed", error: "x" })).toBe("failed");
  });

  it("says a cancelled retrain was cancelled, not that it failed", () => {
    const message = "cancelled by adam; no model was registered from this job";
    const cancelled: Job = { ...job(null), kind: "retrain", status: "cancelled", message };
    expect(describeJob(cancelled)).toBe(`Retraining ${message}`);
  });
});
