// The Relation Network model registry (admin): models, their files, retraining, promotion.
import type { Job, ModelEvent, ModelInfo, PromoteRequest, RetrainRequest } from "@holiscene/schema";
import { BASE, jsonBody, request } from "./client";

const modelUrl = (modelId: string) => `/models/${encodeURIComponent(modelId)}`;

export const modelsApi = {
  listModels: (signal?: AbortSignal) => request<ModelInfo[]>("/models", { signal }),

  /** The model the pipeline and the browser use (404 when none is registered). */
  activeModel: (signal?: AbortSignal) => request<ModelInfo>("/models/active", { signal }),

  listEvents: (signal?: AbortSignal) => request<ModelEvent[]>("/models/events", { signal }),

  /** The newest retrain job, or null when there never was one. */
  latestRetrainJob: (signal?: AbortSignal) => request<Job | null>("/models/retrain", { signal }),

  startRetrain: (body: RetrainRequest) => request<Job>("/models/retrain", jsonBody(body)),

  promote: (modelId: string, body: PromoteRequest) =>
    request<ModelInfo>(`${modelUrl(modelId)}/promote`, jsonBody(body)),

  /** The ONNX file; the same id always serves the same bytes (cached by the browser). */
  onnxUrl: (modelId: string) => `${BASE}${modelUrl(modelId)}/model.onnx`,

  curveUrl: (modelId: string) => `${BASE}${modelUrl(modelId)}/curve.png`,
};
