// The Relation Network in the browser: onnxruntime-web (WASM, one thread, ortRuntime.ts) on the
// same ONNX file the backend runs, fed by preprocess.ts. A session costs about a second to
// create (mostly compiling the wasm), so each model URL gets one session, kept and reused.
import type { Scene, SceneObject } from "@holiscene/schema";
import { RELATION_MODEL } from "@holiscene/schema";
import type { InferenceSession } from "onnxruntime-web";
import { modelsApi } from "../api/models";
import { loadRuntime, type Ort } from "./ortRuntime";
import {
  modelObjects,
  objectInputs,
  type PixelImage,
  type RelationInputs,
  sceneInputs,
} from "./preprocess";
import {
  offTheFloor,
  ruleOutImpossible,
  ruleOutTheWall,
  seenAgainstTheFloor,
} from "./supportGeometry";
import { type PriorsFile, SupportPriors } from "./supportPriors";

export type SupportTypeName = (typeof RELATION_MODEL.support_types)[number];

export const STRUCTURAL_COLUMNS: readonly string[] = RELATION_MODEL.structural_columns;
export const SUPPORT_TYPE_ORDER: readonly SupportTypeName[] = RELATION_MODEL.support_types;
const TYPES = SUPPORT_TYPE_ORDER.length;

/** One answer for an object: a supporter (object id or ceiling/floor/wall) and a type. */
export interface SupportSuggestion {
  supporter: string;
  type: SupportTypeName;
  probability: number;
}

/** An object's answers, most probable first (itself is never among them). */
export interface ObjectSupportScores {
  id: string;
  ranked: SupportSuggestion[];
}

/** Softmax over each row's (N + 3) * 2 logits, in float64 (rows of `logits` [N, N + 3, 2]). */
export function supportProbabilities(logits: ArrayLike<number>, count: number): Float64Array {
  const row = (count + STRUCTURAL_COLUMNS.length) * TYPES;
  if (logits.length !== count * row) {
    throw new Error(
      `expected ${count * row} support logits for ${count} objects, got ${logits.length}`,
    );
  }
  const out = new Float64Array(count * row);
  for (let i = 0; i < count; i++) {
    let max = Number.NEGATIVE_INFINITY;
    for (let k = 0; k < row; k++) max = Math.max(max, logits[i * row + k] as number);
    let sum = 0;
    for (let k = 0; k < row; k++) {
      const e = Math.exp((logits[i * row + k] as number) - max);
      out[i * row + k] = e;
      sum += e;
    }
    for (let k = 0; k < row; k++) out[i * row + k] = (out[i * row + k] as number) / sum;
  }
  return out;
}

/** Each object's (supporter, type) answers by probability; `ids` name the object columns. */
export function rankSupports(
  logits: ArrayLike<number>,
  ids: readonly string[],
): ObjectSupportScores[] {
  return rankProbabilities(supportProbabilities(logits, ids.length), ids);
}

/** Each object's answers by probability, from the softmaxed [N, N + 3, 2] table. */
export function rankProbabilities(
  probabilities: ArrayLike<number>,
  ids: readonly string[],
): ObjectSupportScores[] {
  const columns = [...ids, ...STRUCTURAL_COLUMNS];
  const row = columns.length * TYPES;
  return ids.map((id, i) => {
    const ranked: SupportSuggestion[] = [];
    columns.forEach((supporter, column) => {
      if (column === i) return;
      SUPPORT_TYPE_ORDER.forEach((type, t) => {
        const probability = probabilities[i * row + column * TYPES + t] as number;
        ranked.push({ supporter, type, probability });
      });
    });
    ranked.sort((a, b) => b.probability - a.probability);
    return { id, ranked };
  });
}

/** A scene scored once: what live suggestions decode again after every edit. */
export interface SceneScores {
  ids: string[];
  /** The objects' classes, in the order of `ids`. */
  classes: string[];
  /** The model's counted priors (its priors.json), for Eq. 4.1 decoding; null if it has none. */
  priors: SupportPriors | null;
  /** [N, N + 3, 2] softmax probabilities, flat. */
  probabilities: Float64Array;
  ranked: ObjectSupportScores[];
  /** The registry's version of the model that scored, when it was the active one. */
  modelVersion?: number;
}

export class SupportModel {
  private constructor(
    private readonly ort: Ort,
    private readonly session: InferenceSession,
    readonly url: string,
    readonly priors: SupportPriors | null,
  ) {}

  /** Fetch the ONNX file and create its session (about a second: do it once). */
  static async load(url: string, signal?: AbortSignal): Promise<SupportModel> {
    const [ort, response, priors] = await Promise.all([
      loadRuntime(),
      fetch(url, { signal }), // the ONNX bytes, not a JSON message
      loadPriors(url, signal),
    ]);
    if (!response.ok) throw new Error(`could not fetch the model ${url}: ${response.status}`);
    const bytes = new Uint8Array(await response.arrayBuffer());
    const session = await ort.InferenceSession.create(bytes, {
      executionProviders: ["wasm"],
      graphOptimizationLevel: "all",
    });
    const names = RELATION_MODEL.input_order as readonly string[];
    const missing = names.filter((name) => !session.inputNames.includes(name));
    if (missing.length > 0 || !session.outputNames.includes(RELATION_MODEL.output.name)) {
      await session.release();
      throw new Error(
        `the model ${url} does not follow the contract (inputs ${session.inputNames})`,
      );
    }
    return new SupportModel(ort, session, url, priors);
  }

  /** The raw `support_logits` [N, N + 3, 2], flat. */
  async logits(inputs: RelationInputs): Promise<Float32Array> {
    const { Tensor } = this.ort;
    const n = inputs.count;
    const size = RELATION_MODEL.image_size;
    const maskSize = RELATION_MODEL.mask_size;
    const feeds = {
      image: new Tensor("float32", inputs.image, [1, 3, size, size]),
      masks: new Tensor("float32", inputs.masks, [n, maskSize, maskSize]),
      boxes: new Tensor("float32", inputs.boxes, [n, 4]),
      classes: new Tensor("int64", inputs.classes, [n]),
    };
    const name = RELATION_MODEL.output.name;
    const results = await this.session.run(feeds, [name]);
    const output = results[name];
    try {
      if (output?.type !== "float32") throw new Error(`the model gave no float32 ${name}`);
      const expected = [n, n + STRUCTURAL_COLUMNS.length, TYPES];
      if (output.dims.join() !== expected.join()) {
        throw new Error(`${name} has shape [${output.dims}], expected [${expected}]`);
      }
      return new Float32Array(output.data as Float32Array);
    } finally {
      output?.dispose();
    }
  }

  /** Ranked supporter/type probabilities of each of the scene's (non-structural) objects. */
  async score(objects: readonly SceneObject[], image: PixelImage): Promise<ObjectSupportScores[]> {
    return (await this.probabilities(objects, image)).ranked;
  }

  /** The probability table of the scene's (non-structural) objects, and their rankings. */
  async probabilities(objects: readonly SceneObject[], image: PixelImage): Promise<SceneScores> {
    const kept = modelObjects(objects);
    const ids = kept.map((o) => o.id);
    const classes = kept.map((o) => o.class as string);
    const priors = this.priors;
    if (kept.length === 0) {
      return { ids, classes, priors, probabilities: new Float64Array(0), ranked: [] };
    }
    const logits = await this.logits(sceneInputs(image, kept));
    const probabilities = supportProbabilities(logits, ids.length);
    return { ids, classes, priors, probabilities, ranked: rankProbabilities(probabilities, ids) };
  }
}

/** The priors.json beside a model.onnx (the registry serves both); null when there is none. */
async function loadPriors(modelUrl: string, signal?: AbortSignal): Promise<SupportPriors | null> {
  if (!modelUrl.endsWith("/model.onnx")) return null;
  // A file of the model (written by its training run, like model.onnx), not an API message;
  // a model without one is normal, so any failure means "no priors", never an error or a login.
  try {
    const response = await fetch(modelUrl.replace(/model\.onnx$/, "priors.json"), { signal });
    return response.ok ? SupportPriors.fromJson((await response.json()) as PriorsFile) : null;
  } catch {
    return null;
  }
}

const sessions = new Map<string, Promise<SupportModel>>();

/** The model at `url`, its session created on first use and shared afterwards. */
export function supportModel(url: string): Promise<SupportModel> {
  let model = sessions.get(url);
  if (!model) {
    model = SupportModel.load(url);
    sessions.set(url, model);
    model.catch(() => sessions.delete(url));
  }
  return model;
}

/** The URL of the active model's ONNX file (the model registry's `GET /api/models/active`). */
export async function activeModelUrl(signal?: AbortSignal): Promise<string> {
  const { id } = await modelsApi.activeModel(signal);
  return modelsApi.onnxUrl(id);
}

/**
 * Support scores for a scene's objects with the active model (or the one at `modelUrl`):
 * `imageData` is the scene's photo at its full size (e.g. a canvas's ImageData).
 */
export async function scoreSupports(
  scene: Pick<Scene, "objects" | "image">,
  imageData: PixelImage,
  modelUrl?: string,
): Promise<ObjectSupportScores[]> {
  return (await scoreScene(scene, imageData, modelUrl)).ranked;
}

/** Like scoreSupports, with the probability table (for decoding the tree again). */
export async function scoreScene(
  scene: Pick<Scene, "objects" | "image"> & Partial<Pick<Scene, "camera" | "layout">>,
  imageData: PixelImage,
  modelUrl?: string,
): Promise<SceneScores> {
  if (imageData.width !== scene.image.width || imageData.height !== scene.image.height) {
    throw new Error(
      `the photo is ${imageData.width}x${imageData.height}, the scene says ` +
        `${scene.image.width}x${scene.image.height}`,
    );
  }
  let url = modelUrl;
  let modelVersion: number | undefined;
  if (url === undefined) {
    const active = await modelsApi.activeModel();
    url = modelsApi.onnxUrl(active.id);
    modelVersion = active.version;
  }
  const model = await supportModel(url);
  const scores: SceneScores = { ...(await model.probabilities(scene.objects, imageData)) };
  if (modelVersion !== undefined) scores.modelVersion = modelVersion;
  // What the geometry rules out, as the pipeline's support stage does (supportGeometry.ts).
  const objects = objectInputs(scene.objects);
  const boxes = objects.map((o) => o.bbox);
  const offFloor = offTheFloor(scene.camera, boxes, scene.image.height, objects, scene.image.width);
  const againstFloor = seenAgainstTheFloor(scene.camera, scene.layout?.corners_3d, boxes);
  if (!offFloor.some(Boolean) && !againstFloor.some(Boolean)) return scores;
  ruleOutImpossible(scores.probabilities, boxes, offFloor);
  ruleOutTheWall(scores.probabilities, boxes.length, againstFloor);
  return { ...scores, ranked: rankProbabilities(scores.probabilities, scores.ids) };
}
