// User story: someone with a depth camera imports a room with its depth and checks what the
// depth gave: in the 3D view, "Depth points" shows what the camera saw of each object and what
// shape completion made of it, in two colours a key names, inside the room; on the photo, the
// depth overlay's key says which colour is how far.
import { mkdirSync } from "node:fs";
import path from "node:path";
import { expect, type Page, test } from "@playwright/test";
import { fillUploadWithDepth, submitUploadAndWait } from "../helpers/photo";
import { scene3d } from "../helpers/scene3d";
import { synthesizeFolder } from "../helpers/synthetic";

const SEED = 5; // a synthetic room with its rendered depth.png
const screenshots = path.resolve(import.meta.dirname, "../screenshots");

async function importWithDepth(page: Page, name: string): Promise<void> {
  const dir = synthesizeFolder(SEED);
  await page.goto("/#/");
  await fillUploadWithDepth(page, dir, name);
  await submitUploadAndWait(page);
  await page.getByTestId("upload-open").click();
  await expect(page.getByTestId("scene-title")).toHaveText(name);
}

/** How many of the points (flat x, y, z) lie within `margin` metres of the box given by its
 * 8 corners (BOX_CORNER_SIGNS order: 0-1 along x, 0-4 along y, 0-3 along z). */
function countInside(flat: number[], corners: number[][], margin: number): number {
  const [origin, ...rest] = [corners[0], corners[1], corners[4], corners[3]] as number[][];
  const axes = rest.map((c) => c.map((v, i) => v - (origin?.[i] ?? 0)));
  const lengths = axes.map((a) => Math.hypot(...a));
  let inside = 0;
  for (let p = 0; p < flat.length; p += 3) {
    const d = [0, 1, 2].map((i) => (flat[p + i] ?? 0) - (origin?.[i] ?? 0));
    const fits = axes.every((axis, k) => {
      const along = axis.reduce((sum, v, i) => sum + v * (d[i] ?? 0), 0) / (lengths[k] ?? 1);
      return along >= -margin && along <= (lengths[k] ?? 0) + margin;
    });
    if (fits) inside += 1;
  }
  return inside;
}

test("the 3D view shows each object's depth points inside the room", async ({ page }) => {
  mkdirSync(screenshots, { recursive: true });
  await importWithDepth(page, "room with depth points");
  await expect(page.getByTestId("scene-meta")).toContainText("measured from the depth");
  await expect(page.getByTestId("scene3d-canvas")).toHaveAttribute("data-status", "ready", {
    timeout: 120_000,
  });
  const toggle = page.getByTestId("toggle-depth-points");
  const key = page.getByTestId("depth-points-key");
  await expect(toggle).not.toBeChecked();
  await expect(key).toBeHidden();

  await toggle.check();
  await expect(key).toBeVisible();
  await expect(key).toContainText("seen by the depth camera");
  await expect(key).toContainText("completed shape");
  await expect
    .poll(() => scene3d(page, (p) => p.depthPoints()?.completed.length ?? 0), { timeout: 60_000 })
    .toBeGreaterThan(0);
  const { room, points } = await scene3d(page, (p) => ({
    room: p.roomCorners(),
    points: p.depthPoints(),
  }));
  expect(room).not.toBeNull();
  expect(points?.shown).toBe(true);
  const partial = points?.partial ?? [];
  const completed = points?.completed ?? [];
  expect(partial.length).toBeGreaterThan(0);
  expect(partial.length % 3).toBe(0);
  // What the camera saw is on the room's surfaces and furniture; the completed points may
  // reach a little past a box's side (at most 0.15 of it), never out of the room.
  expect(countInside(partial, room ?? [], 0.05) / (partial.length / 3)).toBeGreaterThan(0.98);
  expect(countInside(completed, room ?? [], 0.3)).toBe(completed.length / 3);
  await page
    .getByTestId("scene3d-panel")
    .screenshot({ path: path.join(screenshots, "depth-points-3d.png") });

  await toggle.uncheck();
  await expect(key).toBeHidden();
  expect(await scene3d(page, (p) => p.depthPoints()?.shown)).toBe(false);
});

test("the depth overlay on the photo has a key from near to far", async ({ page }) => {
  mkdirSync(screenshots, { recursive: true });
  await importWithDepth(page, "room with a depth key");
  // The header's figures say where the scale came from, whole, at a common laptop width.
  await page.setViewportSize({ width: 1280, height: 900 });
  const meta = page.getByTestId("scene-meta");
  await expect(meta).toContainText("(measured from the depth)");
  expect(await meta.evaluate((e) => e.scrollHeight <= e.clientHeight + 1)).toBe(true);
  expect(await meta.evaluate((e) => e.scrollWidth <= e.clientWidth + 1)).toBe(true);
  await page.setViewportSize({ width: 1440, height: 1000 });
  const key = page.getByTestId("depth-key");
  await expect(key).toBeHidden();
  await page.getByTestId("toggle-depth").check();
  await expect(key).toBeVisible();
  await expect(key).toHaveAttribute("data-loaded", "true");
  const near = Number.parseFloat(
    (await page.getByTestId("depth-key-near").textContent())?.replace("near ", "") ?? "",
  );
  const far = Number.parseFloat(
    (await page.getByTestId("depth-key-far").textContent())?.replace("far ", "") ?? "",
  );
  expect(near).toBeGreaterThan(0.3);
  expect(far).toBeGreaterThan(near);
  expect(far).toBeLessThan(15);
  const bar = await page
    .getByTestId("depth-key-bar")
    .evaluate((node) => getComputedStyle(node).backgroundImage);
  expect(bar).toContain("linear-gradient");
  // The key sits in the layer bar beside its toggle, under the photo: it covers no label.
  const photo = await page.getByTestId("photo").boundingBox();
  const box = await key.boundingBox();
  const toggle = await page.getByTestId("toggle-depth").boundingBox();
  expect(photo && box && toggle).toBeTruthy();
  if (photo && box && toggle) {
    expect(box.y).toBeGreaterThanOrEqual(photo.y + photo.height);
    expect(box.x).toBeGreaterThan(toggle.x);
  }
  // The photo panel: bars, photo and the key under it.
  const panel = page.getByTestId("photo-panel");
  await panel.screenshot({ path: path.join(screenshots, "depth-key.png") });
  await page.getByTestId("toggle-depth").uncheck();
  await expect(key).toBeHidden();
});
