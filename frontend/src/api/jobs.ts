// Following a pipeline job until it finishes.
import type { Job } from "@holiscene/schema";
import { api } from "./client";

/** Ended one way or another: the job will not change again. */
export const isFinished = (job: Pick<Job, "status">) =>
  job.status === "succeeded" || job.status === "failed" || job.status === "cancelled";

export interface PollOptions {
  onUpdate?: (job: Job) => void;
  signal?: AbortSignal;
  intervalMs?: number;
}

/** Wait `ms`, or reject as soon as `signal` aborts. */
export function sleep(ms: number, signal?: AbortSignal): Promise<void> {
  return new Promise((resolve, reject) => {
    const timer = setTimeout(resolve, ms);
    signal?.addEventListener(
      "abort",
      () => {
        clearTimeout(timer);
        reject(signal.reason);
      },
      { once: true },
    );
  });
}

/** Poll GET /api/jobs/{id} until the job succeeds or fails; resolve with its final state. */
export async function pollJob(job: Job, options: PollOptions = {}): Promise<Job> {
  const { onUpdate, signal, intervalMs = 500 } = options;
  let current = job;
  onUpdate?.(current);
  while (!isFinished(current)) {
    await sleep(intervalMs, signal);
    current = await api.getJob(current.id, signal);
    onUpdate?.(current);
  }
  return current;
}
