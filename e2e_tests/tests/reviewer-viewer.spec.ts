// User story: a reviewer opens a reconstructed scene in the viser viewer from the scene page
// and sees the room, the objects, the photo's camera and the support arrows, with a panel
// listing every object and its supporter.
import { execFileSync } from "node:child_process";
import { readFileSync } from "node:fs";
import path from "node:path";
import type { ImportResult } from "@holiscene/schema";
import { expect, type Page, test } from "@playwright/test";
import { getScene, waitForJob } from "../helpers/api";
import { scratchDir } from "../helpers/scratch";
import { screenshotPath } from "../helpers/screenshots";

const HOLISCENE = path.resolve(import.meta.dirname, "../../.venv/bin/holiscene");

/** A synthetic room (seed 14: shelves with things on them, a door and a picture on walls). */
function synthesize(): string {
  const out = scratchDir("holiscene-viewer-e2e-");
  execFileSync(HOLISCENE, ["synth", "--seed", "14", "--count", "1", "--workers", "1", "-o", out]);
  return path.join(out, "synth-14");
}

/** The left 60% of the viewer's canvas as a PNG (the panel covers the right). Software
 * WebGL on a busy machine can take many seconds per frame, hence the long timeout. */
async function canvasShot(viewer: Page): Promise<string> {
  const box = await viewer.locator("canvas").first().boundingBox();
  if (!box) throw new Error("the viewer's canvas is not laid out");
  const png = await viewer.screenshot({
    clip: { x: box.x, y: box.y, width: Math.floor(box.width * 0.6), height: box.height },
    timeout: 120_000,
  });
  return png.toString("base64");
}

/** Share of strongly coloured pixels of a shot (the scene's objects and arrows, not the grey
 * room or the white page), and, given a second shot, the share of pixels that differ. */
function pixelShares(viewer: Page, shot: string, other?: string): Promise<number> {
  return viewer.evaluate(
    async ([first, second]) => {
      const read = async (base64: string) => {
        const image = new Image();
        image.src = `data:image/png;base64,${base64}`;
        await image.decode();
        const canvas = document.createElement("canvas");
        canvas.width = image.width;
        canvas.height = image.height;
        const context = canvas.getContext("2d");
        if (!context) throw new Error("no 2D context");
        context.drawImage(image, 0, 0);
        return context.getImageData(0, 0, canvas.width, canvas.height).data;
      };
      const a = await read(first ?? "");
      const b = second ? await read(second) : null;
      let count = 0;
      for (let i = 0; i < a.length; i += 4) {
        const [r, g, bl] = [a[i] ?? 0, a[i + 1] ?? 0, a[i + 2] ?? 0];
        if (b) {
          const d = Math.max(
            Math.abs(r - (b[i] ?? 0)),
            Math.abs(g - (b[i + 1] ?? 0)),
            Math.abs(bl - (b[i + 2] ?? 0)),
          );
          if (d > 16) count += 1;
        } else if (Math.max(r, g, bl) - Math.min(r, g, bl) > 80) {
          count += 1;
        }
      }
      return count / (a.length / 4);
    },
    [shot, other ?? ""],
  );
}

test("opens the scene in viser with every object in its panel", async ({
  page,
  request,
  context,
}) => {
  test.setTimeout(480_000); // software WebGL on a shared 2-core machine
  const folder = synthesize();
  const part = (name: string, mimeType: string) => ({
    name,
    mimeType,
    buffer: readFileSync(path.join(folder, name)),
  });
  const response = await request.post("/api/scenes", {
    multipart: {
      image: part("img.png", "image/png"),
      cam_k: part("cam_K.txt", "text/plain"),
      detections: part("detections.json", "application/json"),
      name: "viewer review",
    },
  });
  expect(response.status(), await response.text()).toBe(201);
  const imported = (await response.json()) as ImportResult;
  if (!imported.job) throw new Error("the import started no pipeline job");
  const job = await waitForJob(request, imported.job.id);
  expect(job.status, job.error ?? "").toBe("succeeded");
  const doc = await getScene(request, imported.scene.id);
  const objects = doc.scene.objects ?? [];
  const placed = objects.filter((o) => o.corners_3d);
  expect(placed.length).toBeGreaterThanOrEqual(5);

  await page.goto(`/#/scenes/${doc.scene_id}`);
  await expect(page.getByTestId("scene-title")).toHaveText("viewer review");
  const [viewer] = await Promise.all([
    context.waitForEvent("page"),
    page.getByTestId("open-viser").click(),
  ]);
  await expect(page.getByTestId("viser-link")).toHaveAttribute(
    "href",
    /^http:\/\/127\.0\.0\.1:\d+$/,
  );
  const url = await page.getByTestId("viser-link").getAttribute("href");
  await viewer.waitForURL(`${url}/`);

  // The 3D canvas, and the scene's nodes drawn in it: class-coloured objects, and support
  // arrows that the panel's "Support arrows" toggle takes away.
  await viewer.setViewportSize({ width: 1200, height: 800 }); // fewer pixels to render in software
  await expect(viewer.locator("canvas").first()).toBeVisible({ timeout: 60_000 });
  await expect
    .poll(async () => pixelShares(viewer, await canvasShot(viewer)), { timeout: 180_000 })
    .toBeGreaterThan(0.01);
  const withArrows = await canvasShot(viewer);
  const arrowsToggle = viewer.getByRole("checkbox", { name: "Support arrows" });
  await arrowsToggle.uncheck();
  await expect
    .poll(async () => pixelShares(viewer, withArrows, await canvasShot(viewer)), {
      timeout: 120_000,
    })
    .toBeGreaterThan(0.0004);
  await arrowsToggle.check();
  // The panel: the scene's summary and one table row per object with its supporter.
  await expect(
    viewer.getByText(`${objects.length} objects (${placed.length} in 3D)`),
  ).toBeVisible();
  const table = viewer.locator("table").filter({ hasText: "supporter" }).last();
  for (const object of objects) {
    const support = doc.scene.supports?.find((s) => s.child === object.id);
    const cells = [object.id, object.class, support?.parent ?? "-", support?.type ?? "-"];
    await expect(table.getByRole("row", { name: new RegExp(`^${cells.join(" ")} `) })).toHaveCount(
      1,
    );
  }
  // Viser's notice about software WebGL (headless Chromium) may cover a corner; it is fine.
  await viewer.screenshot({ path: screenshotPath("reviewer-viewer.png") });

  // An edit saved after the viewer opened: the viewer follows the page by itself, and its
  // open tab shows the new supporter without a reload.
  const link = page.getByTestId("viser-link");
  await expect(link).toHaveText(`viewer of revision ${doc.revision}`);
  const child = doc.scene.supports?.find((s) => s.parent !== "wall")?.child ?? "";
  const childClass = objects.find((o) => o.id === child)?.class ?? "";
  await page.getByTestId(`supporter-select-${child}`).selectOption("wall");
  await page.keyboard.press("Control+s");
  await expect(page.getByTestId("save-status")).toHaveAttribute("data-state", "saved");
  await expect(link).toHaveText(`viewer of revision ${doc.revision + 1}`, { timeout: 30_000 });
  await expect(
    table.getByRole("row", { name: new RegExp(`^${child} ${childClass} wall `) }),
  ).toHaveCount(1, { timeout: 60_000 });

  // The same button again reuses the scene's viewer.
  await page.getByTestId("open-viser").click();
  await expect(link).toHaveAttribute("href", url ?? "");
  await expect(link).toHaveText(`viewer of revision ${doc.revision + 1}`);
});
