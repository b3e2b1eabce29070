// Benchmark: object detection in the browser (the app's detector-check page, onnxruntime-web
// WASM on one thread, the app's active detector) on a synthetic 640 x 480 photo and, when the
// real photos beside the repository exist (../shared/data/real), on real ones, served to the page
// from disk (never copied into the repository). Each run stretches the photo to the model's
// input, runs the model and decodes the boxes. The figures (session creation, the first run,
// the median of the others) are printed and attached; nothing is asserted about them (the
// target is at most 1.5 s per photo).
import { existsSync, readFileSync } from "node:fs";
import path from "node:path";
import { expect, type Page, test } from "@playwright/test";
import type { DetectionTimings, EncodedPhoto } from "../../frontend/src/inference/detectorCheck";

const WIDTH = 640;
const HEIGHT = 480;
const RUNS = 8; // the first, and seven more for the median
const REAL = path.resolve(import.meta.dirname, "../../../shared/data/real");
const REAL_PHOTOS = ["t3d-1", "im3d-1"];
const TARGET_MS = 1500;

/** A small seeded generator (mulberry32), so every run times the same photo. */
function random(seed: number): () => number {
  let state = seed >>> 0;
  return () => {
    state = (state + 0x6d2b79f5) >>> 0;
    let t = state;
    t = Math.imul(t ^ (t >>> 15), t | 1);
    t ^= t + Math.imul(t ^ (t >>> 7), t | 61);
    return ((t ^ (t >>> 14)) >>> 0) / 4294967296;
  };
}

/** A 640 x 480 'room': a gradient, a few filled rectangles, light noise. */
function syntheticPhoto(): EncodedPhoto {
  const next = random(20260518);
  const rgb = Buffer.alloc(WIDTH * HEIGHT * 3);
  const shapes = Array.from({ length: 8 }, () => ({
    x0: next() * WIDTH,
    y0: next() * HEIGHT,
    w: 30 + next() * 250,
    h: 30 + next() * 200,
    colour: [next() * 255, next() * 255, next() * 255],
  }));
  for (let y = 0; y < HEIGHT; y++) {
    for (let x = 0; x < WIDTH; x++) {
      const at = (y * WIDTH + x) * 3;
      let colour = [200 - (y / HEIGHT) * 80, 190 - (y / HEIGHT) * 60, 170];
      for (const s of shapes) {
        if (x >= s.x0 && x < s.x0 + s.w && y >= s.y0 && y < s.y0 + s.h) colour = s.colour;
      }
      for (let c = 0; c < 3; c++) {
        rgb[at + c] = Math.max(0, Math.min(255, Math.round((colour[c] as number) + next() * 6)));
      }
    }
  }
  return { width: WIDTH, height: HEIGHT, rgb_base64: rgb.toString("base64") };
}

const median = (values: number[]) => {
  const sorted = [...values].sort((a, b) => a - b);
  return sorted[Math.floor(sorted.length / 2)] as number;
};

function summary(name: string, t: DetectionTimings): Record<string, number | string> {
  const later = t.totalMs.slice(1);
  return {
    photo: `${name} (${t.width}x${t.height})`,
    firstMs: Math.round(t.totalMs[0] as number),
    medianMs: Math.round(median(later)),
    minMs: Math.round(Math.min(...later)),
    maxMs: Math.round(Math.max(...later)),
    preprocessMs: Number(median(t.preprocessMs).toFixed(1)),
    modelMs: Math.round(median(t.runMs)),
    decodeMs: Number(median(t.decodeMs).toFixed(2)),
    boxes: t.boxes.length,
  };
}

async function time(page: Page, photo: string | EncodedPhoto): Promise<DetectionTimings> {
  return page.evaluate(
    ({ photo, runs }) => {
      if (!window.holisceneDetector) throw new Error("the detector check page did not start");
      return window.holisceneDetector.time(photo, runs);
    },
    { photo, runs: RUNS },
  );
}

test("object detection in the browser: time per photo (WASM, one thread)", async ({
  page,
}, testInfo) => {
  await page.goto("/detector-check.html");
  const loaded = await page.evaluate(() => {
    if (!window.holisceneDetector) throw new Error("the detector check page did not start");
    return window.holisceneDetector.load();
  });
  const rows = [summary("synthetic", await time(page, syntheticPhoto()))];

  const real = REAL_PHOTOS.filter((name) => existsSync(path.join(REAL, name, "img.jpg")));
  for (const name of real) {
    // The page fetches the photo as the scene page does (decoded by the browser, not here).
    const url = `/benchmark-photos/${name}.jpg`;
    await page.route(`**${url}`, (route) =>
      route.fulfill({
        body: readFileSync(path.join(REAL, name, "img.jpg")),
        contentType: "image/jpeg",
      }),
    );
    rows.push(summary(name, await time(page, url)));
  }
  if (real.length === 0) console.log(`no real photos in ${REAL}: the synthetic photo only`);

  const lines = [
    `object detection in Chromium (onnxruntime-web WASM, 1 thread, ${loaded.info.name}, ` +
      `${(loaded.info.model_bytes / 1e6).toFixed(1)} MB): session ${Math.round(loaded.loadMs)} ms`,
    ...rows.map(
      (r) =>
        `  ${r.photo}: first ${r.firstMs} ms, median ${r.medianMs} ms of ${RUNS - 1} ` +
        `(min ${r.minMs}, max ${r.maxMs}; preprocess ${r.preprocessMs}, model ${r.modelMs}, ` +
        `decode ${r.decodeMs} ms), ${r.boxes} boxes` +
        (Number(r.medianMs) > TARGET_MS ? `  (over the ${TARGET_MS} ms target)` : ""),
    ),
  ];
  for (const line of lines) console.log(line);
  await testInfo.attach("detector-benchmark.json", {
    body: JSON.stringify({ sessionMs: loaded.loadMs, runs: RUNS, rows }, null, 1),
    contentType: "application/json",
  });
  expect(rows.length).toBe(1 + real.length);
});
