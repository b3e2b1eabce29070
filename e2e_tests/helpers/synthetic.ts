// Synthetic scenes with known truth: `holiscene synth` writes a folder (img.png, cam_K.txt,
// detections.json, gt.json); importing it runs the pipeline, whose guesses can then be
// compared with gt.json. Object ids match: the pipeline names detection i "o{i}", and the
// generator writes detection i for gt object "o{i}".
import { execFileSync } from "node:child_process";
import { readFileSync } from "node:fs";
import path from "node:path";
import type { ImportResult, SceneDocument, SupportRelation } from "@holiscene/schema";
import { type APIRequestContext, expect } from "@playwright/test";
import { getScene, waitForJob } from "./api";
import { scratchDir } from "./scratch";

const HOLISCENE = path.resolve(import.meta.dirname, "../../.venv/bin/holiscene");

export interface SyntheticScene {
  dir: string;
  truth: SupportRelation[];
}

/** Generate `count` synthetic scenes from `seed` (scene i uses seed + i). */
export function synthesize(seed: number, count: number): SyntheticScene[] {
  const out = scratchDir("holiscene-synth-");
  execFileSync(
    HOLISCENE,
    ["synth", "--seed", String(seed), "--count", String(count), "-o", out, "--workers", "1"],
    { stdio: "pipe" },
  );
  return Array.from({ length: count }, (_, i) => {
    const dir = path.join(out, `synth-${seed + i}`);
    const gt = JSON.parse(readFileSync(path.join(dir, "gt.json"), "utf8")) as {
      supports: SupportRelation[];
    };
    return { dir, truth: gt.supports };
  });
}

/** One synthetic scene folder (img.png, cam_K.txt, detections.json, gt.json) for `seed`. */
export function synthesizeFolder(seed: number): string {
  const [scene] = synthesize(seed, 1);
  if (!scene) throw new Error(`holiscene synth wrote no scene for seed ${seed}`);
  return scene.dir;
}

const part = (dir: string, name: string, mimeType: string) => ({
  name,
  mimeType,
  buffer: readFileSync(path.join(dir, name)),
});

/** Import a synthetic folder and wait for the pipeline's guesses. */
export async function importSynthetic(
  request: APIRequestContext,
  scene: SyntheticScene,
  name: string,
): Promise<SceneDocument> {
  const response = await request.post("/api/scenes", {
    multipart: {
      image: part(scene.dir, "img.png", "image/png"),
      cam_k: part(scene.dir, "cam_K.txt", "text/plain"),
      detections: part(scene.dir, "detections.json", "application/json"),
      name,
    },
  });
  expect(response.status(), await response.text()).toBe(201);
  const imported = (await response.json()) as ImportResult;
  if (imported.job) {
    const job = await waitForJob(request, imported.job.id);
    expect(job.status, job.error ?? "").toBe("succeeded");
  }
  return getScene(request, imported.scene.id);
}

/** The objects whose predicted supporter or type differs from the truth. */
export function wrongEdges(doc: SceneDocument, truth: readonly SupportRelation[]): string[] {
  const predicted = new Map((doc.scene.supports ?? []).map((s) => [s.child, s]));
  return truth
    .filter((t) => {
      const p = predicted.get(t.child);
      return !p || p.parent !== t.parent || p.type !== t.type;
    })
    .map((t) => t.child);
}
