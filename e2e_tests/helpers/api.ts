// Seeding and checking scenes through the HTTP API, as the app's users would not: directly.
import { readFileSync } from "node:fs";
import path from "node:path";
import type {
  ImportResult,
  Job,
  RevisionInfo,
  SceneDocument,
  SupportRelation,
} from "@holiscene/schema";
import { type APIRequestContext, expect } from "@playwright/test";

/** A real photo with its intrinsics and 2D detections (see ../shared/data/real). */
export const T3D_5 = path.resolve(import.meta.dirname, "../../../shared/data/real/t3d-5");
/** Another real photo: scenes of one photo share a side of the retraining's held-out split. */
export const T3D_1 = path.resolve(import.meta.dirname, "../../../shared/data/real/t3d-1");

function filePart(dir: string, name: string, mimeType: string) {
  return { name, mimeType, buffer: readFileSync(path.join(dir, name)) };
}

/** Import a photo folder (img.jpg, cam_K.txt, detections.json) and wait for its pipeline. */
export async function seedScene(
  request: APIRequestContext,
  dir: string,
  name: string,
): Promise<SceneDocument> {
  const response = await request.post("/api/scenes", {
    multipart: {
      image: filePart(dir, "img.jpg", "image/jpeg"),
      cam_k: filePart(dir, "cam_K.txt", "text/plain"),
      detections: filePart(dir, "detections.json", "application/json"),
      name,
    },
  });
  expect(response.status(), await response.text()).toBe(201);
  const imported = (await response.json()) as ImportResult;
  if (imported.job) {
    const job = await waitForJob(request, imported.job.id);
    expect(job.status, job.error ?? "").toBe("succeeded");
  }
  return getScene(request, imported.scene.id);
}

/** A real photo (t3d-5 unless `dir` says) with an empty detections.json: a scene without
 * objects. */
export async function importWithoutObjects(
  request: APIRequestContext,
  name: string,
  dir: string = T3D_5,
): Promise<string> {
  const response = await request.post("/api/scenes", {
    multipart: {
      image: filePart(dir, "img.jpg", "image/jpeg"),
      cam_k: filePart(dir, "cam_K.txt", "text/plain"),
      detections: {
        name: "detections.json",
        mimeType: "application/json",
        buffer: Buffer.from("[]"),
      },
      name,
    },
  });
  expect(response.status(), await response.text()).toBe(201);
  const imported = (await response.json()) as ImportResult;
  if (imported.job) expect((await waitForJob(request, imported.job.id)).status).toBe("succeeded");
  return imported.scene.id;
}

export async function waitForJob(
  request: APIRequestContext,
  jobId: string,
  timeoutMs = 120_000,
): Promise<Job> {
  let job: Job | undefined;
  await expect
    .poll(
      async () => {
        job = (await (await request.get(`/api/jobs/${jobId}`)).json()) as Job;
        return job.status;
      },
      { timeout: timeoutMs, intervals: [250, 500, 1000] },
    )
    .toMatch(/succeeded|failed/);
  if (!job) throw new Error(`job ${jobId} was never read`);
  return job;
}

async function getJson<T>(request: APIRequestContext, url: string): Promise<T> {
  const response = await request.get(url);
  expect(response.ok(), `${url}: ${response.status()}`).toBe(true);
  return (await response.json()) as T;
}

export const getScene = (request: APIRequestContext, sceneId: string) =>
  getJson<SceneDocument>(request, `/api/scenes/${sceneId}`);

export const getRevisions = (request: APIRequestContext, sceneId: string) =>
  getJson<RevisionInfo[]>(request, `/api/scenes/${sceneId}/revisions`);

/** Post `edits` on `doc`'s revision; the revision they made. */
export async function postEdits(
  request: APIRequestContext,
  doc: SceneDocument,
  author: string,
  edits: object[],
): Promise<SceneDocument> {
  const response = await request.post(`/api/scenes/${doc.scene_id}/edits`, {
    data: { base_revision: doc.revision, author, edits },
  });
  expect(response.status(), await response.text()).toBe(200);
  return (await response.json()) as SceneDocument;
}

export function supportOf(doc: SceneDocument, child: string): SupportRelation | undefined {
  return doc.scene.supports?.find((s) => s.child === child);
}
