// The object detector check page (detector-check.html, served with the app): runs the active
// detector in this browser with onnxruntime-web on a photo, and times it. Playwright drives it
// through `window.holisceneDetector` to check the browser against the shared vectors
// (shared_schema/vectors/detector_model.json) and to measure detection; a person can open it
// to see whether the browser runs the detector and how fast.
import { mountCheckPage } from "./checkPage";
import {
  activeDetector,
  type DetectorInfo,
  type DetectorModel,
  detectorModel,
  suggesterDetector,
} from "./detector";
import { type DetectedBox, decodeDetections, detectorInput } from "./detectorTensor";
import type { PixelImage } from "./preprocess";
import { photoPixels } from "./supportSuggestions";

/** A photo as the shared vectors store it: RGB bytes row by row, zlib-packed or not, base64. */
export interface EncodedPhoto {
  width: number;
  height: number;
  encoding?: "zlib";
  rgb_base64: string;
}

export interface RawResult {
  raw: number[];
  boxes: DetectedBox[];
  /** The input tensor's float32 bytes' sha256 (the vectors store it). */
  inputSha256: string;
  preprocessMs: number;
  runMs: number;
}

export interface DetectionTimings {
  width: number;
  height: number;
  /** Each run: preprocessing, the model and decoding together (the first run included). */
  totalMs: number[];
  preprocessMs: number[];
  runMs: number[];
  decodeMs: number[];
  boxes: DetectedBox[];
}

export interface DetectorCheck {
  /** Create the active detector's session (or the suggester's); what it is and how long that
   * took. */
  load(which?: "active" | "suggester"): Promise<{ info: DetectorInfo; loadMs: number }>;
  /** The sha256 of a photo's input tensor's float32 bytes (no model needed). */
  inputSha256(photo: EncodedPhoto): Promise<string>;
  /** The raw rows and decoded boxes of a photo (`threshold`: the contract's by default). */
  raw(photo: EncodedPhoto, threshold?: number): Promise<RawResult>;
  /** Time `runs` detections of a photo (a URL the page can fetch, or an encoded photo). */
  time(photo: string | EncodedPhoto, runs: number): Promise<DetectionTimings>;
}

async function rgbBytes(photo: EncodedPhoto): Promise<Uint8Array> {
  const bytes = Uint8Array.from(atob(photo.rgb_base64), (c) => c.charCodeAt(0));
  if (photo.encoding !== "zlib") return bytes;
  const stream = new Blob([bytes]).stream().pipeThrough(new DecompressionStream("deflate"));
  return new Uint8Array(await new Response(stream).arrayBuffer());
}

/** The photo as a canvas would give it: RGBA ImageData. */
async function decodePhoto(photo: EncodedPhoto): Promise<PixelImage> {
  const { width, height } = photo;
  const rgb = await rgbBytes(photo);
  if (rgb.length !== width * height * 3) throw new Error(`not ${width}x${height} RGB bytes`);
  const data = new ImageData(width, height);
  for (let i = 0; i < width * height; i++) {
    data.data.set(rgb.subarray(3 * i, 3 * i + 3), 4 * i);
    data.data[4 * i + 3] = 255;
  }
  return data;
}

async function sha256(values: Float32Array<ArrayBuffer>): Promise<string> {
  const digest = await crypto.subtle.digest("SHA-256", values);
  return Array.from(new Uint8Array(digest), (b) => b.toString(16).padStart(2, "0")).join("");
}

let current: Promise<DetectorModel> | null = null;

function model(): Promise<DetectorModel> {
  if (!current) throw new Error("no detector loaded: call load() first");
  return current;
}

const check: DetectorCheck = {
  async load(which = "active") {
    const start = performance.now();
    const info = await (which === "suggester" ? suggesterDetector() : activeDetector());
    current = detectorModel(info);
    await current;
    return { info, loadMs: performance.now() - start };
  },

  async inputSha256(photo) {
    return sha256(detectorInput(await decodePhoto(photo)));
  },

  async raw(photo, threshold) {
    const m = await model();
    const pixels = await decodePhoto(photo);
    const start = performance.now();
    const input = detectorInput(pixels);
    const ran = performance.now();
    // Hashed first: the run hands the tensor's buffer to the runtime's worker.
    const inputSha256 = await sha256(input);
    const hashMs = performance.now() - ran;
    const raw = await m.raw(input);
    const runMs = performance.now() - ran - hashMs;
    return {
      raw: Array.from(raw),
      boxes: decodeDetections(raw, pixels.width, pixels.height, m.mapping, threshold),
      inputSha256,
      preprocessMs: ran - start,
      runMs,
    };
  },

  async time(photo, runs) {
    const m = await model();
    const pixels = typeof photo === "string" ? await photoPixels(photo) : await decodePhoto(photo);
    const timings: DetectionTimings = {
      width: pixels.width,
      height: pixels.height,
      totalMs: [],
      preprocessMs: [],
      runMs: [],
      decodeMs: [],
      boxes: [],
    };
    for (let i = 0; i < runs; i++) {
      const start = performance.now();
      const result = await m.detect(pixels);
      timings.totalMs.push(performance.now() - start);
      timings.preprocessMs.push(result.preprocessMs);
      timings.runMs.push(result.runMs);
      timings.decodeMs.push(result.decodeMs);
      timings.boxes = result.boxes;
    }
    return timings;
  },
};

declare global {
  interface Window {
    holisceneDetector?: DetectorCheck;
  }
}

window.holisceneDetector = check;

// For a person: load the active detector on request and say how long it took.
mountCheckPage({
  id: "detector-check",
  title: "Object detector in the browser",
  about: "onnxruntime-web (WebAssembly, one thread) on the app's object detector.",
  what: "detector",
  load: () =>
    check
      .load()
      .then(
        ({ info, loadMs }) =>
          `${info.name} (${info.id}): session ready in ${Math.round(loadMs)} ms.`,
      ),
});
