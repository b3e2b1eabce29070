// The Relation Network check page (relation-check.html, served with the app): runs the active
// model (or any model URL of the app) in this browser with onnxruntime-web on a photo and its
// objects, and times it. Playwright drives it through `window.holisceneRelation` to check the
// browser against the shared vectors and to measure support scoring; a person can open it to
// see whether the browser runs the model and how fast.
import type { SceneObject } from "@holiscene/schema";
import { mountCheckPage } from "./checkPage";
import { modelObjects, type PixelImage, sceneInputs } from "./preprocess";
import {
  activeModelUrl,
  type ObjectSupportScores,
  type SupportModel,
  supportModel,
} from "./supportModel";

/** A photo as the shared vectors store it: RGB bytes, row by row, in base64. */
export interface EncodedImage {
  width: number;
  height: number;
  rgb_base64: string;
}

export interface LogitsResult {
  ids: string[];
  logits: number[];
  preprocessMs: number;
  runMs: number;
}

export interface Timings {
  count: number;
  preprocessMs: number[];
  runMs: number[];
  scoreMs: number[]; // preprocessing, the model and the ranked probabilities together
}

export interface RelationCheck {
  /** Create the session of `url` (default: the active model's); the time it took. */
  load(url?: string): Promise<{ url: string; loadMs: number }>;
  /** The model's raw logits for a photo and its objects. */
  logits(image: EncodedImage, objects: SceneObject[]): Promise<LogitsResult>;
  /** Ranked supporter/type probabilities per object. */
  score(image: EncodedImage, objects: SceneObject[]): Promise<ObjectSupportScores[]>;
  /** Time `runs` support scorings of one scene on the loaded session. */
  time(image: EncodedImage, objects: SceneObject[], runs: number): Promise<Timings>;
}

/** The photo as a canvas would give it: RGBA ImageData. */
function decodeImage({ width, height, rgb_base64 }: EncodedImage): PixelImage {
  const rgb = Uint8Array.from(atob(rgb_base64), (c) => c.charCodeAt(0));
  if (rgb.length !== width * height * 3) throw new Error(`not ${width}x${height} RGB bytes`);
  const data = new ImageData(width, height);
  for (let i = 0; i < width * height; i++) {
    data.data.set(rgb.subarray(3 * i, 3 * i + 3), 4 * i);
    data.data[4 * i + 3] = 255;
  }
  return data;
}

let current: Promise<SupportModel> | null = null;

function model(): Promise<SupportModel> {
  if (!current) throw new Error("no model loaded: call load() first");
  return current;
}

const check: RelationCheck = {
  async load(url) {
    const start = performance.now();
    const resolved = url ?? (await activeModelUrl());
    current = supportModel(resolved);
    await current;
    return { url: resolved, loadMs: performance.now() - start };
  },

  async logits(image, objects) {
    const m = await model();
    const pixels = decodeImage(image);
    const start = performance.now();
    const inputs = sceneInputs(pixels, objects);
    const ran = performance.now();
    const logits = await m.logits(inputs);
    return {
      ids: modelObjects(objects).map((o) => o.id),
      logits: Array.from(logits),
      preprocessMs: ran - start,
      runMs: performance.now() - ran,
    };
  },

  async score(image, objects) {
    return (await model()).score(objects, decodeImage(image));
  },

  async time(image, objects, runs) {
    const m = await model();
    const pixels = decodeImage(image);
    const timings: Timings = { count: 0, preprocessMs: [], runMs: [], scoreMs: [] };
    for (let i = 0; i < runs; i++) {
      const start = performance.now();
      const inputs = sceneInputs(pixels, objects);
      const ran = performance.now();
      await m.logits(inputs);
      const end = performance.now();
      timings.preprocessMs.push(ran - start);
      timings.runMs.push(end - ran);
      const scoreStart = performance.now();
      const scores = await m.score(objects, pixels);
      timings.scoreMs.push(performance.now() - scoreStart);
      timings.count = scores.length;
    }
    return timings;
  },
};

declare global {
  interface Window {
    holisceneRelation?: RelationCheck;
  }
}

window.holisceneRelation = check;

// For a person: load the active model on request and say how long it took.
mountCheckPage({
  id: "relation-check",
  title: "Relation Network in the browser",
  about: "onnxruntime-web (WebAssembly, one thread) on the app's support model.",
  what: "model",
  load: () =>
    check.load().then(({ url, loadMs }) => `${url}: session ready in ${Math.round(loadMs)} ms.`),
});
