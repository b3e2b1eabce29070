// Datasets uploaded as a .zip (POST /api/imports), imported by the server in the background.
import type { ImportJob } from "@holiscene/schema";
import { inBackground, request } from "./client";
import { isFinished, sleep } from "./jobs";

export const importsApi = {
  /** Upload the zip; the server unpacks and recognises it before answering (4xx if not). */
  start(archive: File, runPipeline: boolean): Promise<ImportJob> {
    const form = new FormData();
    form.append("archive", archive);
    form.append("run_pipeline", String(runPipeline));
    return request<ImportJob>("/imports", { method: "POST", body: form });
  },

  /** Only pollImport asks, so this is a background request (api/client.ts). */
  get: (jobId: string, signal?: AbortSignal) =>
    request<ImportJob>(`/imports/${encodeURIComponent(jobId)}`, inBackground({ signal })),
};

/** Poll the import until it ends, telling `onUpdate` each state; resolve with the last. */
export async function pollImport(
  job: ImportJob,
  onUpdate: (job: ImportJob) => void,
  signal?: AbortSignal,
  intervalMs = 700,
): Promise<ImportJob> {
  let current = job;
  onUpdate(current);
  while (!isFinished(current)) {
    await sleep(intervalMs, signal);
    current = await importsApi.get(current.id, signal);
    onUpdate(current);
  }
  return current;
}
