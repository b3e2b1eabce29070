// The object detectors in the browser agree with the backend: the app's detector-check page
// fetches the active detector from the app (GET /api/detector/active, then its model.onnx), and
// the suggester (GET /api/detector/suggester; its vectors are suggester_model.json),
// runs it with onnxruntime-web (WASM, one thread, the wasm file served by the app) on each photo
// of the shared vectors (shared_schema/vectors/detector_model.json), stretching the photo itself,
// and its raw rows must match onnxruntime's in Python within 1e-4 (scores, and box corners as
// shares of the 512-pixel input; rows of near-equal scores in either order: matchRows); its
// input tensor is the backend's bit for bit, and its decoded boxes are the backend's.
import { createHash } from "node:crypto";
import { readFileSync } from "node:fs";
import path from "node:path";
import { type APIRequestContext, expect, type Page, test } from "@playwright/test";
import type { DetectorInfo } from "../../frontend/src/inference/detector";
import type { EncodedPhoto } from "../../frontend/src/inference/detectorCheck";
import { watchAppOnly } from "../helpers/appOnly";

const vectorsFile = (name: string) =>
  path.resolve(import.meta.dirname, "../../shared_schema/vectors", name);
const RAW_TOLERANCE = 1e-4;
const INPUT_SIZE = 512;
// Decoded boxes in photo pixels: the corners' differences (a few thousandths of an input pixel)
// scaled to the photo.
const BOX_TOLERANCE = 0.01;

interface ExpectedBox {
  bbox: number[];
  score: number;
  class: string;
  source_class: string;
}

interface PhotoCase {
  name: string;
  image: EncodedPhoto;
  expected: {
    images: { float32_sha256: string };
    detections: { shape: number[]; data: number[] };
    boxes: ExpectedBox[];
    boxes_low_threshold: ExpectedBox[];
  };
}

interface Vectors {
  model: { sha256: string };
  low_threshold: number;
  tolerance: { detections: number };
  cases: PhotoCase[];
  preprocess_cases: { name: string; image: EncodedPhoto; expected: PhotoCase["expected"] }[];
}

/**
 * How far apart two values of column `k` of a row are: box corners (0-3) in shares of the input
 * size (as the model's boxes are relative to it), scores (4) as they are, class indices (5)
 * infinitely unless equal.
 */
function difference(a: number, b: number, k: number): number {
  if (k < 4) return Math.abs(a - b) / INPUT_SIZE;
  if (k === 4) return Math.abs(a - b);
  return a === b ? 0 : Number.POSITIVE_INFINITY;
}

interface RowMatch {
  /** Largest difference (see `difference`) between matched rows. */
  worst: number;
  worstScore: number;
  /** In input pixels. */
  worstCorner: number;
  /** Rows matched to a row at another place (near-equal scores in another order). */
  reordered: number;
  /** Rows on one side only, with scores within the tolerance of the cut or of another row of
   * their class on their side (a flat heatmap's neighbouring cells: a peak or not by the last
   * bits). */
  onOneSide: number;
  problems: string[];
}

/**
 * The browser's rows against the backend's. The model lists its best peaks best first; peaks
 * whose scores differ by less than the tolerance may come in another order on another runtime
 * (a photo of one colour has dozens), and the last rows may be others when their scores are
 * that close to the 100th; of two neighbouring cells of one class and score, whether both are
 * peaks is decided in the last bits. So each row must match a row of the other side (same
 * class, every value within the tolerance), at its own place or another; a row left over must
 * score within the tolerance of the cut or of another row of its class on its side; and each
 * side must list its rows best first. The backend's export check is the same rule
 * (backend/src/holiscene/learning/detector/row_matching.py).
 */
function matchRows(actual: readonly number[], expected: readonly number[], tol: number): RowMatch {
  const rows = expected.length / 6;
  const row = (values: readonly number[], i: number) => values.slice(i * 6, i * 6 + 6);
  const close = (a: number[], e: number[]) =>
    a.every((v, k) => difference(v, e[k] as number, k) <= tol);
  const partner = new Int32Array(rows).fill(-1);
  const taken = new Uint8Array(rows);
  for (let i = 0; i < rows; i++) {
    if (close(row(actual, i), row(expected, i))) {
      partner[i] = i;
      taken[i] = 1;
    }
  }
  let reordered = 0;
  for (let i = 0; i < rows; i++) {
    if ((partner[i] as number) >= 0) continue;
    const a = row(actual, i);
    let best = -1;
    for (let j = 0; j < rows; j++) {
      if (taken[j] || !close(a, row(expected, j))) continue;
      if (best < 0 || Math.abs(j - i) < Math.abs(best - i)) best = j;
    }
    if (best >= 0) {
      partner[i] = best;
      taken[best] = 1;
      reordered++;
    }
  }
  const cut = expected[(rows - 1) * 6 + 4] as number;
  const problems: string[] = [];
  let onOneSide = 0;
  const twinned = (values: readonly number[], i: number) => {
    const [score, cls] = [values[i * 6 + 4] as number, values[i * 6 + 5]];
    for (let k = 0; k < rows; k++) {
      const close = Math.abs((values[k * 6 + 4] as number) - score) <= tol;
      if (k !== i && values[k * 6 + 5] === cls && close) return true;
    }
    return false;
  };
  const leftOver = (side: string, values: readonly number[], i: number) => {
    const score = values[i * 6 + 4] as number;
    if (Math.abs(score - cut) <= tol || twinned(values, i)) onOneSide++;
    else problems.push(`${side} row ${i} [${row(values, i).join(", ")}] has no match`);
  };
  for (let i = 0; i < rows; i++) if ((partner[i] as number) < 0) leftOver("browser", actual, i);
  for (let j = 0; j < rows; j++) if (!taken[j]) leftOver("backend", expected, j);
  for (const [side, values] of [
    ["browser", actual],
    ["backend", expected],
  ] as const) {
    for (let i = 1; i < rows; i++) {
      const rise = (values[i * 6 + 4] as number) - (values[(i - 1) * 6 + 4] as number);
      if (rise > tol) problems.push(`${side} row ${i} is out of score order`);
    }
  }
  const match = { worst: 0, worstScore: 0, worstCorner: 0, reordered, onOneSide, problems };
  partner.forEach((j, i) => {
    if (j < 0) return;
    const a = row(actual, i);
    const e = row(expected, j);
    a.forEach((v, k) => {
      const d = Math.abs(v - (e[k] as number));
      match.worst = Math.max(match.worst, difference(v, e[k] as number, k));
      if (k === 4) match.worstScore = Math.max(match.worstScore, d);
      if (k < 4) match.worstCorner = Math.max(match.worstCorner, d);
    });
  });
  return match;
}

type Which = "active" | "suggester";

async function agreesOnVectors(
  { page, request, baseURL }: { page: Page; request: APIRequestContext; baseURL?: string },
  which: Which,
  vectorsPath: string,
): Promise<void> {
  const vectors = JSON.parse(readFileSync(vectorsPath, "utf8")) as Vectors;
  expect(vectors.tolerance.detections).toBe(RAW_TOLERANCE);

  const served = await request.get(`/api/detector/${which}`);
  expect(served.status(), await served.text()).toBe(200);
  const info = (await served.json()) as DetectorInfo;
  const modelFile = await request.get(info.model_url);
  expect(modelFile.status()).toBe(200);
  const sha256 = createHash("sha256")
    .update(await modelFile.body())
    .digest("hex");
  expect(sha256).toBe(info.model_sha256);
  expect(sha256, "the vectors are stale: run `make detector-vectors`").toBe(vectors.model.sha256);

  const requests = watchAppOnly(page, baseURL);
  const modelFetched = page.waitForResponse((r) => new URL(r.url()).pathname === info.model_url);
  await page.goto("/detector-check.html");
  const loaded = await page.evaluate((which) => {
    if (!window.holisceneDetector) throw new Error("the detector check page did not start");
    return window.holisceneDetector.load(which);
  }, which);
  expect(loaded.info.model_url).toBe(info.model_url);
  expect((await modelFetched).status()).toBe(200);
  requests.expectWasmFromApp();

  const report: string[] = [];
  for (const c of vectors.cases) {
    for (const [threshold, expected] of [
      [undefined, c.expected.boxes],
      [vectors.low_threshold, c.expected.boxes_low_threshold],
    ] as const) {
      const result = await page.evaluate(
        ({ image, threshold }) => {
          if (!window.holisceneDetector) throw new Error("the detector check page did not start");
          return window.holisceneDetector.raw(image, threshold);
        },
        { image: c.image, threshold },
      );
      expect(result.inputSha256, `${c.name}: input tensor`).toBe(c.expected.images.float32_sha256);
      const want = c.expected.detections.data;
      expect(result.raw.length).toBe(want.length);
      const match = matchRows(result.raw, want, RAW_TOLERANCE);
      expect(match.problems, c.name).toEqual([]);
      expect(match.worst, c.name).toBeLessThanOrEqual(RAW_TOLERANCE);
      expect(result.boxes.map((b) => `${b.cls} ${b.sourceClass}`)).toEqual(
        expected.map((b) => `${b.class} ${b.source_class}`),
      );
      let boxWorst = 0;
      result.boxes.forEach((box, i) => {
        box.bbox.forEach((v, k) => {
          boxWorst = Math.max(boxWorst, Math.abs(v - (expected[i]?.bbox[k] as number)));
        });
      });
      expect(boxWorst, `${c.name}: boxes`).toBeLessThanOrEqual(BOX_TOLERANCE);
      if (threshold !== undefined) {
        report.push(
          `${c.name}: max |browser - backend| scores ${match.worstScore.toExponential(2)}, ` +
            `box corners ${match.worstCorner.toExponential(2)} input px; ` +
            `${match.reordered} rows reordered, ${match.onOneSide} on one side only (ties); ` +
            `decoded boxes ${boxWorst.toExponential(2)} px over ${result.boxes.length} boxes ` +
            `(preprocess ${result.preprocessMs.toFixed(1)} ms, run ${result.runMs.toFixed(0)} ms)`,
        );
      }
    }
  }
  // The photos the model is not run on (a pixel, a column, a row): the input tensor alone.
  for (const c of vectors.preprocess_cases) {
    const sha = await page.evaluate(
      (image) => window.holisceneDetector?.inputSha256(image) ?? "",
      c.image,
    );
    expect(sha, `${c.name}: input tensor`).toBe(c.expected.images.float32_sha256);
  }
  console.log(`${which} detector, browser vs backend (session ${loaded.loadMs.toFixed(0)} ms):`);
  for (const line of report) console.log(`  ${line}`);
  requests.expectNothingForeign();
}

test("the browser runs the app's detector and agrees with the backend on the shared vectors", ({
  page,
  request,
  baseURL,
}) => agreesOnVectors({ page, request, baseURL }, "active", vectorsFile("detector_model.json")));

// The scene page's guesses come from the suggester, run in the browser too: its own vectors.
test("the browser runs the suggester and agrees with the backend on its shared vectors", ({
  page,
  request,
  baseURL,
}) =>
  agreesOnVectors({ page, request, baseURL }, "suggester", vectorsFile("suggester_model.json")));
