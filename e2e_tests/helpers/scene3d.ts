// Seeding scenes from any input folder (real or synthetic), and reading the 3D view and the
// layout editor through the probes they put on their elements (scene3dView.ts: the canvas's
// `scene3dProbe`; layoutEditor.ts: the layout bar's `layoutProbe`).
import { existsSync, readFileSync } from "node:fs";
import path from "node:path";
import type { ImportResult, SceneDocument } from "@holiscene/schema";
import { type APIRequestContext, expect, type Page } from "@playwright/test";
import { getScene, waitForJob } from "./api";

export { synthesizeFolder as synthesize } from "./synthetic";

/** Import an input folder (img.jpg or img.png, cam_K.txt, detections.json), run its pipeline. */
export async function seedFolder(
  request: APIRequestContext,
  dir: string,
  name: string,
  detections?: unknown,
): Promise<SceneDocument> {
  const image = existsSync(path.join(dir, "img.jpg")) ? "img.jpg" : "img.png";
  const part = (file: string, mimeType: string) => ({
    name: file,
    mimeType,
    buffer: readFileSync(path.join(dir, file)),
  });
  const boxes = detections
    ? {
        name: "detections.json",
        mimeType: "application/json",
        buffer: Buffer.from(JSON.stringify(detections)),
      }
    : part("detections.json", "application/json");
  const response = await request.post("/api/scenes", {
    multipart: {
      image: part(image, image.endsWith(".png") ? "image/png" : "image/jpeg"),
      cam_k: part("cam_K.txt", "text/plain"),
      detections: boxes,
      name,
    },
    timeout: 60_000,
  });
  expect(response.status(), await response.text()).toBe(201);
  const imported = (await response.json()) as ImportResult;
  if (!imported.job) throw new Error("the import started no pipeline job");
  const job = await waitForJob(request, imported.job.id, 400_000);
  expect(job.status, job.error ?? "").toBe("succeeded");
  return getScene(request, imported.scene.id);
}

/** Open a scene page and wait for its 3D view to show the scene. */
export async function openScene(page: Page, sceneId: string): Promise<void> {
  await page.goto(`/#/scenes/${sceneId}`);
  await expect(page.getByTestId("scene3d-canvas")).toHaveAttribute("data-status", "ready", {
    timeout: 120_000,
  });
}

/** Wait until the page has drawn two more animation frames. */
export function nextFrames(page: Page): Promise<void> {
  return page.evaluate(
    () =>
      new Promise<void>((done) => requestAnimationFrame(() => requestAnimationFrame(() => done()))),
  );
}

interface Probe {
  frames: number;
  renderMs: number[];
  roomCorners(): number[][] | null;
  cameraPose(): { pitchDeg: number; rollDeg: number } | null;
  frustumShown(): boolean;
  photoOnFrustum(): boolean;
  arrows(): { child: string; parent: string; type: string }[];
  screenPointOf(id: string): { x: number; y: number } | null;
  objectColour(id: string): number[] | null;
  renderInfo(): { calls: number; triangles: number; width: number; height: number };
  glbLoad(): { ms: number; triangles: number } | null;
  orbit(azimuth: number): void;
  depthPoints(): { shown: boolean; partial: number[]; completed: number[] } | null;
}

/** Evaluate a function of the 3D view's probe in the page. */
export function scene3d<T, A = undefined>(
  page: Page,
  read: (probe: Probe, arg: A) => T,
  arg?: A,
): Promise<T> {
  return page.getByTestId("scene3d-canvas").evaluate(
    (canvas, [source, value]) => {
      const probe = (canvas as unknown as { scene3dProbe?: Probe }).scene3dProbe;
      if (!probe) throw new Error("the 3D view has no probe");
      return (new Function(`return (${source})`)() as (p: Probe, a: unknown) => T)(probe, value);
    },
    [read.toString(), arg] as const,
  );
}

interface LayoutProbe {
  fitTimes(): number[];
  live(): { corners3d: number[][]; pitchDeg: number; rollDeg: number } | null;
  error(): string | null;
}

export function layoutProbe<T>(page: Page, read: (probe: LayoutProbe) => T): Promise<T> {
  return page.getByTestId("layout-bar").evaluate((bar, source) => {
    const probe = (bar as unknown as { layoutProbe?: LayoutProbe }).layoutProbe;
    if (!probe) throw new Error("the layout bar has no probe");
    return (new Function(`return (${source})`)() as (p: LayoutProbe) => T)(probe);
  }, read.toString());
}

/** The largest difference between two lists of points. */
export function maxDifference(a: number[][] | null, b: number[][] | null): number {
  if (!a || !b) return Number.POSITIVE_INFINITY;
  let largest = 0;
  a.forEach((point, i) => {
    point.forEach((v, j) => {
      largest = Math.max(largest, Math.abs(v - (b[i]?.[j] ?? Number.NaN)));
    });
  });
  return Number.isNaN(largest) ? Number.POSITIVE_INFINITY : largest;
}
