// The Relation Network in the browser agrees with the backend: the app's relation-check page
// fetches the default model from the app's model registry, runs it with onnxruntime-web (WASM,
// one thread, the wasm file served by the app) on each case of the shared vectors
// (shared_schema/vectors/relation_model.json), preprocessing the photo and masks itself, and
// its logits must match onnxruntime's in Python within 1e-4. Then the scene page's model
// suggestions: the active model, scored in the browser on a real photo.
import { createHash } from "node:crypto";
import { readFileSync } from "node:fs";
import path from "node:path";
import type { ModelInfo, SceneObject } from "@holiscene/schema";
import { expect, test } from "@playwright/test";
import type { EncodedImage } from "../../frontend/src/inference/relationCheck";
import { seedScene, T3D_5 } from "../helpers/api";
import { watchAppOnly } from "../helpers/appOnly";

const VECTORS = path.resolve(
  import.meta.dirname,
  "../../shared_schema/vectors/relation_model.json",
);
const LOGIT_TOLERANCE = 1e-4;
const STRUCTURAL_COLUMNS = ["ceiling", "floor", "wall"];
const SUPPORT_TYPES = ["below", "behind"];

interface VectorCase {
  name: string;
  image: EncodedImage;
  objects: SceneObject[];
  model_objects: string[];
  expected: { support_logits: { shape: number[]; data: number[] } };
}

interface Vectors {
  model: { sha256: string };
  tolerance: { support_logits: number };
  cases: VectorCase[];
}

/** Each row's best (supporter, type) by the expected logits, skipping the object itself. */
function bestAnswers(c: VectorCase): string[] {
  const ids = c.model_objects;
  const columns = [...ids, ...STRUCTURAL_COLUMNS];
  const row = columns.length * SUPPORT_TYPES.length;
  const logits = c.expected.support_logits.data;
  return ids.map((_, i) => {
    let best = -1;
    for (let k = 0; k < row; k++) {
      if (Math.floor(k / SUPPORT_TYPES.length) === i) continue;
      if (best < 0 || (logits[i * row + k] as number) > (logits[i * row + best] as number))
        best = k;
    }
    const column = Math.floor(best / SUPPORT_TYPES.length);
    return `${columns[column]} ${SUPPORT_TYPES[best % SUPPORT_TYPES.length]}`;
  });
}

test("the browser runs the app's model and agrees with the backend on the shared vectors", async ({
  page,
  request,
  baseURL,
}) => {
  const vectors = JSON.parse(readFileSync(VECTORS, "utf8")) as Vectors;
  expect(vectors.tolerance.support_logits).toBe(LOGIT_TOLERANCE);

  // The app registers the committed default model on first start; the vectors were made from
  // that very file. (Other specs may retrain and promote models: the default stays listed.)
  const listed = await request.get("/api/models");
  expect(listed.status(), await listed.text()).toBe(200);
  const models = (await listed.json()) as ModelInfo[];
  const reference = models.find((m) => m.status === "default");
  if (!reference) throw new Error(`no default model among ${models.map((m) => m.id)}`);
  const modelUrl = `/api/models/${encodeURIComponent(reference.id)}/model.onnx`;
  const modelFile = await request.get(modelUrl);
  expect(modelFile.status()).toBe(200);
  const sha256 = createHash("sha256")
    .update(await modelFile.body())
    .digest("hex");
  expect(sha256, "the vectors are stale: run `make relation-vectors`").toBe(vectors.model.sha256);

  const requests = watchAppOnly(page, baseURL);
  const modelFetched = page.waitForResponse((r) => new URL(r.url()).pathname === modelUrl);
  await page.goto("/relation-check.html");
  const loaded = await page.evaluate((url) => {
    if (!window.holisceneRelation) throw new Error("the relation check page did not start");
    return window.holisceneRelation.load(url);
  }, modelUrl);
  expect(loaded.url).toBe(modelUrl);
  expect((await modelFetched).status()).toBe(200);
  requests.expectWasmFromApp();

  const report: string[] = [];
  for (const c of vectors.cases) {
    const result = await page.evaluate(
      ({ image, objects }) => {
        if (!window.holisceneRelation) throw new Error("the relation check page did not start");
        return window.holisceneRelation.logits(image, objects);
      },
      { image: c.image, objects: c.objects },
    );
    expect(result.ids).toEqual(c.model_objects);
    const expected = c.expected.support_logits.data;
    expect(result.logits.length).toBe(expected.length);
    let worst = 0;
    let at = -1;
    result.logits.forEach((value, i) => {
      const difference = Math.abs(value - (expected[i] as number));
      if (!(difference <= worst)) {
        worst = difference;
        at = i;
      }
    });
    report.push(
      `${c.name}: max |browser - backend| ${worst.toExponential(2)}` +
        ` (preprocess ${result.preprocessMs.toFixed(1)} ms, run ${result.runMs.toFixed(1)} ms)`,
    );
    expect(worst, `${c.name}: logit ${at}`).toBeLessThanOrEqual(LOGIT_TOLERANCE);

    // The ranked probabilities name supporters and types in the contract's column order.
    const scores = await page.evaluate(
      ({ image, objects }) => window.holisceneRelation?.score(image, objects) ?? [],
      { image: c.image, objects: c.objects },
    );
    expect(scores.map((s) => s.id)).toEqual(c.model_objects);
    expect(scores.map((s) => `${s.ranked[0]?.supporter} ${s.ranked[0]?.type}`)).toEqual(
      bestAnswers(c),
    );
    for (const s of scores) {
      const total = s.ranked.reduce((sum, r) => sum + r.probability, 0);
      expect(total).toBeGreaterThan(0.999);
      expect(total).toBeLessThanOrEqual(1 + 1e-9);
      expect(s.ranked.some((r) => r.supporter === s.id)).toBe(false);
    }
  }
  console.log(`relation network, browser vs backend (session ${loaded.loadMs.toFixed(0)} ms):`);
  for (const line of report) console.log(`  ${line}`);
  requests.expectNothingForeign();
});

test("the scene page shows the model's suggested supporter of each object", async ({
  page,
  request,
}) => {
  const seeded = await seedScene(request, T3D_5, "t3d-5 suggestions");
  const objects = (seeded.scene.objects ?? []).filter((o) => !STRUCTURAL_COLUMNS.includes(o.class));
  expect(objects.length).toBeGreaterThanOrEqual(3);
  await page.goto(`/#/scenes/${seeded.scene_id}`);
  await expect(page.getByTestId("object-table")).toBeVisible();
  // Live suggestions score the scene when it opens; the button scores it again.
  await page.getByTestId("suggest-supports").click();
  await expect(page.getByTestId("suggestion-status")).toContainText(
    `${objects.length} objects scored in`,
    { timeout: 60_000 },
  );
  // It names the registry's active model, whose scores these are.
  const active = (await (await request.get("/api/models/active")).json()) as { version: number };
  await expect(page.getByTestId("suggestion-status")).toContainText(
    `ms by the Relation Network v${active.version}`,
  );
  // The model runs in onnxruntime-web's own worker, never on the page's thread (where a
  // scoring would hold an edit's redraw back).
  expect(
    page
      .workers()
      .map((w) => w.url())
      .filter((url) => /\/assets\/ort[.-]/.test(url)),
  ).toHaveLength(1);
  const candidates = [...objects.map((o) => o.id), ...STRUCTURAL_COLUMNS];
  for (const object of objects) {
    const badge = page.getByTestId(`support-suggestion-${object.id}`);
    await expect(badge).toBeVisible();
    // "model: o5 99%"; the type is said only when it is "behind" on an object.
    const match = /^model: (\S+)( · behind)? (\d+)%$/.exec((await badge.textContent()) ?? "");
    expect(match, `suggestion of ${object.id}`).not.toBeNull();
    expect(candidates).toContain(match?.[1]);
    expect(match?.[1]).not.toBe(object.id);
    await expect(badge).toHaveAttribute("data-supporter", match?.[1] ?? "");
    await expect(badge).toHaveAttribute("data-type", /^(below|behind)$/);
  }
});
