// Typed client of the HoliScene HTTP API (served by `holiscene serve` under /api).
import type {
  DepthKey,
  DepthPoints,
  EditRequest,
  ImportResult,
  Job,
  RevisionInfo,
  SceneDocument,
  SceneSummary,
  ViewerInfo,
} from "@holiscene/schema";
import { ApiError, ConflictError, describeDetail } from "./errors";

export const BASE = "/api";

async function readDetail(response: Response): Promise<unknown> {
  const text = await response.text();
  try {
    const body: unknown = JSON.parse(text);
    return body && typeof body === "object" && "detail" in body
      ? (body as { detail: unknown }).detail
      : body;
  } catch {
    return text || null;
  }
}

/**
 * Told when an answer is 401 (no session, or it ended), with the server's reason (e.g. the
 * account was disabled): main.ts then shows the login page.
 */
export const sessionEvents: { onUnauthorized: ((reason: string | null) => void) | null } = {
  onUnauthorized: null,
};

async function fetchOk(path: string, init: RequestInit, accept: string): Promise<Response> {
  const response = await fetch(`${BASE}${path}`, {
    ...init,
    headers: { Accept: accept, ...init.headers },
  });
  if (!response.ok) {
    const detail = await readDetail(response);
    if (response.status === 401 && !path.startsWith("/auth/")) {
      sessionEvents.onUnauthorized?.(describeDetail(detail));
    }
    if (response.status === 409) throw new ConflictError(detail);
    throw new ApiError(response.status, detail, `${response.status} ${response.statusText}`);
  }
  return response;
}

export async function request<T>(path: string, init: RequestInit = {}): Promise<T> {
  const response = await fetchOk(path, init, "application/json");
  if (response.status === 204) return undefined as T; // no content (logout, ...)
  return (await response.json()) as T;
}

/** A file the server sends (zip, ...), with the name its Content-Disposition gives. */
export async function requestFile(
  path: string,
  init: RequestInit = {},
): Promise<{ blob: Blob; filename: string | null }> {
  const response = await fetchOk(path, init, "*/*");
  const disposition = response.headers.get("Content-Disposition") ?? "";
  const filename = /filename="([^"]+)"/.exec(disposition)?.[1] ?? null;
  return { blob: await response.blob(), filename };
}

/**
 * Marks a request the page makes by itself (polling), not because of something a person did:
 * the server answers it as usual but does not count it as activity, so a forgotten tab still
 * reaches the session's idle timeout (backend api/deps.py).
 */
export const BACKGROUND_HEADER = "X-Holiscene-Background";

export function inBackground(init: RequestInit = {}): RequestInit {
  return { ...init, headers: { ...init.headers, [BACKGROUND_HEADER]: "1" } };
}

export function jsonBody(body: unknown): RequestInit {
  return {
    method: "POST",
    headers: { "Content-Type": "application/json" },
    body: JSON.stringify(body),
  };
}

export interface SceneImport {
  image: File;
  camK?: File | null;
  detections?: File | null;
  /** The user's names for the boxes' classes (read only with detections). */
  classMap?: File | null;
  /** Depth registered to the photo: a 16-bit PNG of millimetres or a .npy of float metres. */
  depth?: File | null;
  name?: string;
}

const sceneUrl = (sceneId: string) => `/scenes/${encodeURIComponent(sceneId)}`;

export const api = {
  listScenes: (signal?: AbortSignal) => request<SceneSummary[]>("/scenes", { signal }),

  importScene(input: SceneImport): Promise<ImportResult> {
    const form = new FormData();
    form.append("image", input.image);
    if (input.camK) form.append("cam_k", input.camK);
    if (input.detections) form.append("detections", input.detections);
    if (input.classMap) form.append("class_map", input.classMap);
    if (input.depth) form.append("depth", input.depth);
    if (input.name?.trim()) form.append("name", input.name.trim());
    return request<ImportResult>("/scenes", { method: "POST", body: form });
  },

  getScene: (sceneId: string, signal?: AbortSignal) =>
    request<SceneDocument>(sceneUrl(sceneId), { signal }),

  imageUrl: (sceneId: string) => `${BASE}${sceneUrl(sceneId)}/image`,

  /** The depth given with the photo as a colour picture of its size (scenes with depth). */
  depthPreviewUrl: (sceneId: string) => `${BASE}${sceneUrl(sceneId)}/depth-preview.png`,

  /** The depth overlay's key: the depths its colours span, and the colours near to far. */
  depthKey: (sceneId: string, signal?: AbortSignal) =>
    request<DepthKey>(`${sceneUrl(sceneId)}/depth-key`, { signal }),

  /** Each object's partial and completed points from the depth (scenes with depth). */
  depthPoints: (sceneId: string, revision: number, signal?: AbortSignal) =>
    request<DepthPoints>(`${sceneUrl(sceneId)}/depth-points?revision=${revision}`, { signal }),

  glbUrl: (sceneId: string, revision: number) =>
    `${BASE}${sceneUrl(sceneId)}/scene.glb?revision=${revision}`,

  startPipeline: (sceneId: string) =>
    request<Job>(`${sceneUrl(sceneId)}/pipeline-jobs`, { method: "POST" }),

  /** Only pollJob asks for a job, so this is a background request (see BACKGROUND_HEADER). */
  getJob: (jobId: string, signal?: AbortSignal) =>
    request<Job>(`/jobs/${encodeURIComponent(jobId)}`, inBackground({ signal })),

  postEdits: (sceneId: string, body: EditRequest) =>
    request<SceneDocument>(`${sceneUrl(sceneId)}/edits`, jsonBody(body)),

  listRevisions: (sceneId: string, signal?: AbortSignal) =>
    request<RevisionInfo[]>(`${sceneUrl(sceneId)}/revisions`, { signal }),

  getRevision: (sceneId: string, revision: number, signal?: AbortSignal) =>
    request<SceneDocument>(`${sceneUrl(sceneId)}/revisions/${revision}`, { signal }),

  /** Start (or reuse) the scene's viser viewer, on 127.0.0.1 (backend api/routes/viewer.py). */
  openViewer: (sceneId: string) =>
    request<ViewerInfo>(`${sceneUrl(sceneId)}/viewer`, { method: "POST" }),
};
