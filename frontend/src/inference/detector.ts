// The object detector in the browser: onnxruntime-web (WASM, one thread, ortRuntime.ts) on the
// same ONNX file the backend runs (runtime.py's Detector), fed and decoded by detectorTensor.ts.
// The app serves the active detector's files (GET /api/detector/active, then its model_url), and
// the suggester's (GET /api/detector/suggester);
// the model is about 8 MB and its session takes a moment to create, so each model URL gets one
// session, kept and reused.
import { DETECTOR_MODEL, type DetectorInfo } from "@holiscene/schema";
import type { InferenceSession } from "onnxruntime-web";
import { request } from "../api/client";
import {
  type DetectedBox,
  decodeDetections,
  detectorInput,
  INPUT_SIZE,
  type LabelMapping,
  labelMapping,
  SCORE_THRESHOLD,
} from "./detectorTensor";
import { loadRuntime, type Ort } from "./ortRuntime";
import type { PixelImage } from "./preprocess";

/** GET /api/detector/active (backend api/routes/detector.py), a contract type. */
export type { DetectorInfo };

/** What one detection gave, with its timings (milliseconds). */
export interface Detection {
  boxes: DetectedBox[];
  /** The model's raw `detections` rows, flat [1, 100, 6]. */
  raw: Float32Array;
  preprocessMs: number;
  runMs: number;
  decodeMs: number;
}

/** Bytes of the model fetched so far (total: the size, when the server says it). */
export type LoadProgress = (loaded: number, total: number | null) => void;

const ROWS = DETECTOR_MODEL.output.shape[1];
const ROW = DETECTOR_MODEL.output.shape[2];

/** The active detector's description (404: none is installed). */
export function activeDetector(signal?: AbortSignal): Promise<DetectorInfo> {
  return request<DetectorInfo>("/detector/active", { signal });
}

/** The suggester's description: the detector whose boxes the scene page offers as guesses
 * (GET /api/detector/suggester; 404: none is installed). */
export function suggesterDetector(signal?: AbortSignal): Promise<DetectorInfo> {
  return request<DetectorInfo>("/detector/suggester", { signal });
}

/** The body of `response`, telling `onProgress` how much has come. */
async function readAll(response: Response, onProgress?: LoadProgress): Promise<Uint8Array> {
  const length = Number(response.headers.get("Content-Length"));
  const total = Number.isFinite(length) && length > 0 ? length : null;
  if (!response.body || !onProgress) return new Uint8Array(await response.arrayBuffer());
  const parts: Uint8Array[] = [];
  let loaded = 0;
  const reader = response.body.getReader();
  for (;;) {
    const { done, value } = await reader.read();
    if (done) break;
    parts.push(value);
    loaded += value.length;
    onProgress(loaded, total);
  }
  const bytes = new Uint8Array(loaded);
  let at = 0;
  for (const part of parts) {
    bytes.set(part, at);
    at += part.length;
  }
  return bytes;
}

export class DetectorModel {
  private constructor(
    private readonly ort: Ort,
    private readonly session: InferenceSession,
    readonly info: DetectorInfo,
    readonly mapping: LabelMapping,
  ) {}

  /** Fetch the ONNX file and create its session (do it once: see `detectorModel`). */
  static async load(info: DetectorInfo, onProgress?: LoadProgress): Promise<DetectorModel> {
    const mapping = labelMapping(info);
    // The model is bytes, read with progress, not a JSON message: a plain fetch.
    const [ort, response] = await Promise.all([loadRuntime(), fetch(info.model_url)]);
    if (!response.ok) {
      throw new Error(`could not fetch the detector ${info.model_url}: ${response.status}`);
    }
    const bytes = await readAll(response, onProgress);
    const session = await ort.InferenceSession.create(bytes, {
      executionProviders: ["wasm"],
      graphOptimizationLevel: "all",
    });
    const input = DETECTOR_MODEL.input.name;
    const output = DETECTOR_MODEL.output.name;
    if (!session.inputNames.includes(input) || !session.outputNames.includes(output)) {
      await session.release();
      throw new Error(
        `the detector ${info.model_url} does not follow the contract (inputs ` +
          `${session.inputNames}, outputs ${session.outputNames}; needs ${input} and ${output})`,
      );
    }
    return new DetectorModel(ort, session, info, mapping);
  }

  /** The raw `detections` [1, 100, 6] of an input tensor [1, S, S, 3] (flat). */
  async raw(input: Float32Array): Promise<Float32Array> {
    const { Tensor } = this.ort;
    const feeds = {
      [DETECTOR_MODEL.input.name]: new Tensor("float32", input, [1, INPUT_SIZE, INPUT_SIZE, 3]),
    };
    const name = DETECTOR_MODEL.output.name;
    const results = await this.session.run(feeds, [name]);
    const output = results[name];
    try {
      if (output?.type !== "float32") throw new Error(`the detector gave no float32 ${name}`);
      if (output.dims.join() !== [1, ROWS, ROW].join()) {
        throw new Error(`${name} has shape [${output.dims}], expected [1, ${ROWS}, ${ROW}]`);
      }
      return new Float32Array(output.data as Float32Array);
    } finally {
      output?.dispose();
    }
  }

  /** NYU-40 boxes in the photo's pixels (`image`: the photo at its full size, RGB or RGBA). */
  async detect(image: PixelImage, scoreThreshold: number = SCORE_THRESHOLD): Promise<Detection> {
    const start = performance.now();
    const input = detectorInput(image);
    const ran = performance.now();
    const raw = await this.raw(input);
    const decoding = performance.now();
    const boxes = decodeDetections(raw, image.width, image.height, this.mapping, scoreThreshold);
    const end = performance.now();
    return {
      boxes,
      raw,
      preprocessMs: ran - start,
      runMs: decoding - ran,
      decodeMs: end - decoding,
    };
  }
}

const sessions = new Map<string, Promise<DetectorModel>>();

/**
 * The detector described by `info`, its session created on first use and shared afterwards
 * (only the first caller hears the download's progress).
 */
export function detectorModel(
  info: DetectorInfo,
  onProgress?: LoadProgress,
): Promise<DetectorModel> {
  let model = sessions.get(info.model_url);
  if (!model) {
    model = DetectorModel.load(info, onProgress);
    sessions.set(info.model_url, model);
    model.catch(() => sessions.delete(info.model_url));
  }
  return model;
}
