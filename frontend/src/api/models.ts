// The model registry (admin): models, their files, retraining, promotion. Two kinds, each with
// its own versions, active model and history: the Relation Network ("relation", the default)
// and the object detector ("detector").
import type {
  Job,
  ModelEvent,
  ModelInfo,
  PromoteRequest,
  RetrainReadiness,
  RetrainRequest,
} from "@holiscene/schema";
import type { ModelKind } from "../router";
import { BASE, jsonBody, request } from "./client";

const modelUrl = (modelId: string) => `/models/${encodeURIComponent(modelId)}`;
const ofKind = (path: string, kind: ModelKind) =>
  kind === "relation" ? path : `${path}?kind=${encodeURIComponent(kind)}`;

export const modelsApi = {
  listModels: (signal?: AbortSignal, kind: ModelKind = "relation") =>
    request<ModelInfo[]>(ofKind("/models", kind), { signal }),

  /** The model the pipeline and the browser use (404 when none is registered). */
  activeModel: (signal?: AbortSignal, kind: ModelKind = "relation") =>
    request<ModelInfo>(ofKind("/models/active", kind), { signal }),

  listEvents: (signal?: AbortSignal, kind: ModelKind = "relation") =>
    request<ModelEvent[]>(ofKind("/models/events", kind), { signal }),

  /** The newest retrain job of a kind, or null when there never was one. */
  latestRetrainJob: (signal?: AbortSignal, kind: ModelKind = "relation") =>
    request<Job | null>(ofKind("/models/retrain", kind), { signal }),

  /** How many stored scenes a retraining would learn from, and how many it needs. */
  retrainReadiness: (signal?: AbortSignal, kind: ModelKind = "relation") =>
    request<RetrainReadiness>(ofKind("/models/retrain/readiness", kind), { signal }),

  startRetrain: (body: RetrainRequest, kind: ModelKind = "relation") =>
    request<Job>(ofKind("/models/retrain", kind), jsonBody(body)),

  /** Stop a queued or running retrain job at its next step; it registers nothing. */
  cancelRetrain: (jobId: string) =>
    request<Job>(`/models/retrain/${encodeURIComponent(jobId)}/cancel`, { method: "POST" }),

  /** Make a model the active one of its kind (a rollback when it is older). */
  promote: (modelId: string, body: PromoteRequest) =>
    request<ModelInfo>(`${modelUrl(modelId)}/promote`, jsonBody(body)),

  /** The ONNX file; the same id always serves the same bytes (cached by the browser). */
  onnxUrl: (modelId: string) => `${BASE}${modelUrl(modelId)}/model.onnx`,

  curveUrl: (modelId: string) => `${BASE}${modelUrl(modelId)}/curve.png`,
};
