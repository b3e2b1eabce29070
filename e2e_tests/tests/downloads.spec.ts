// User story: an annotator takes a scene out of the workbench: from the scene page its
// scene.json, scene.glb and the photo's objects as COCO JSON; from the list, several scenes
// at once as one zip, which "Import a dataset" (here or on another server) takes back.
import { readFileSync } from "node:fs";
import path from "node:path";
import type { ImportResult, Scene } from "@holiscene/schema";
import type { Download, Page } from "@playwright/test";
import { expect, test } from "@playwright/test";
import { getScene, postEdits, seedScene, T3D_5 } from "../helpers/api";
import { importZip } from "../helpers/datasetImport";
import { nextDialog } from "../helpers/dialogs";
import { openScene } from "../helpers/photo";
import { screenshotPath } from "../helpers/screenshots";
import { readZip } from "../helpers/zip";

interface CocoFile {
  images: { id: number; file_name: string; width: number; height: number }[];
  categories: { id: number; name: string }[];
  annotations: {
    holiscene_id: string;
    category_id: number;
    bbox: number[];
    area: number;
    segmentation: { counts: number[]; size: [number, number] } | number[][];
  }[];
}

/** Import t3d-5 without running the pipeline: a scene with boxes but no 3D scene. */
async function importUnplaced(page: Page, name: string): Promise<string> {
  const response = await page.request.post("/api/scenes", {
    multipart: {
      image: {
        name: "img.jpg",
        mimeType: "image/jpeg",
        buffer: readFileSync(path.join(T3D_5, "img.jpg")),
      },
      name,
      run_pipeline: "false",
    },
  });
  expect(response.status(), await response.text()).toBe(201);
  return ((await response.json()) as ImportResult).scene.id;
}

async function downloadFrom(page: Page, item: string): Promise<Download> {
  const menu = page.getByTestId("download-menu");
  if (!(await menu.evaluate((details: HTMLDetailsElement) => details.open))) {
    await page.getByTestId("download-button").click();
  }
  const [download] = await Promise.all([
    page.waitForEvent("download"),
    page.getByTestId(item).click(),
  ]);
  return download;
}

const contents = async (download: Download) => readFileSync(await download.path());

/** The COCO counts cover the whole photo, and the mask's pixels are the area. */
function checkRle(rle: { counts: number[]; size: [number, number] }, area: number): void {
  const [height, width] = rle.size;
  expect(rle.counts.reduce((a, b) => a + b, 0)).toBe(width * height);
  expect(rle.counts.filter((_, i) => i % 2 === 1).reduce((a, b) => a + b, 0)).toBe(area);
}

test("the scene page downloads scene.json, scene.glb and COCO JSON", async ({ page }) => {
  const doc = await seedScene(page.request, T3D_5, "t3d-5 downloads");
  await openScene(page, doc.scene_id);
  await page.getByTestId("download-button").click();
  await expect(page.getByTestId("download-glb")).toBeVisible();
  await expect(page.getByTestId("download-no-glb")).toBeHidden();
  await page.screenshot({ path: screenshotPath("download-menu.png") });

  const sceneJson = await downloadFrom(page, "download-scene-json");
  expect(sceneJson.suggestedFilename()).toBe("t3d-5_downloads.scene.json");
  const saved = (await getScene(page.request, doc.scene_id)).scene;
  expect(JSON.parse((await contents(sceneJson)).toString()) as Scene).toEqual(saved);
  await expect(page.getByTestId("download-menu")).not.toHaveAttribute("open");

  const glb = await downloadFrom(page, "download-glb");
  expect(glb.suggestedFilename()).toBe("t3d-5_downloads.glb");
  const glbBytes = await contents(glb);
  expect(glbBytes.subarray(0, 4).toString()).toBe("glTF");
  expect(glbBytes.readUInt32LE(8)).toBe(glbBytes.length); // the header's total length

  const cocoDownload = await downloadFrom(page, "download-coco");
  expect(cocoDownload.suggestedFilename()).toBe("t3d-5_downloads.coco.json");
  const coco = JSON.parse((await contents(cocoDownload)).toString()) as CocoFile;
  expect(coco.images).toEqual([
    { id: 1, file_name: saved.image.file, width: saved.image.width, height: saved.image.height },
  ]);
  expect(coco.categories).toHaveLength(40);
  const categoryOf = new Map(coco.categories.map((c) => [c.id, c.name]));
  expect(coco.annotations.map((a) => a.holiscene_id)).toEqual(saved.objects.map((o) => o.id));
  for (const annotation of coco.annotations) {
    const object = saved.objects.find((o) => o.id === annotation.holiscene_id);
    if (!object) throw new Error(`no object ${annotation.holiscene_id}`);
    expect(categoryOf.get(annotation.category_id)).toBe(object.class);
    const [x1, y1, x2, y2] = object.bbox;
    expect(annotation.bbox).toEqual([x1, y1, x2 - x1, y2 - y1]);
    expect(object.mask).not.toBeNull(); // the pipeline cut one for every object
    if (Array.isArray(annotation.segmentation)) throw new Error("a mask became a polygon");
    checkRle(annotation.segmentation, annotation.area);
  }

  // An object removed after the pipeline made the 3D scene: the menu says the file is older.
  const current = await getScene(page.request, doc.scene_id);
  const gone = current.scene.objects?.[0]?.id ?? "o0";
  await postEdits(page.request, current, "e2e", [{ kind: "remove_object", id: gone }]);
  await page.reload();
  await expect(page.getByTestId("scene-title")).toHaveText("t3d-5 downloads");
  await page.getByTestId("download-button").click();
  await expect(page.getByTestId("download-glb")).toContainText(
    `made at revision ${doc.revision}; since then 1 removed`,
  );
  await page.keyboard.press("Escape");
  // The 3D panel counts from the same revision after the reload, and submitting asks first:
  // once submitted, nobody can re-place the objects.
  await expect(page.getByTestId("placement-notice-text")).toContainText("(1 removed)");
  await expect(page.getByTestId("workflow-state")).toHaveText("in annotation"); // the edit took it
  const submit = page.getByTestId("workflow-submit");
  await expect(submit).toBeEnabled();
  const question = nextDialog(page, "dismiss");
  await submit.click();
  expect(await question).toContain("The 3D scene was made before these changes: 1 removed.");
  await expect(page.getByTestId("workflow-state")).toHaveText("in annotation");

  // Escape closes the menu; a scene the pipeline has not placed has no scene.glb to offer.
  await page.getByTestId("download-button").click();
  await page.keyboard.press("Escape");
  await expect(page.getByTestId("download-menu")).not.toHaveAttribute("open");
  const unplaced = await importUnplaced(page, "t3d-5 not placed");
  await page.goto(`/#/scenes/${unplaced}`);
  await expect(page.getByTestId("scene-title")).toHaveText("t3d-5 not placed");
  const glbAsked: string[] = [];
  page.on("request", (r) => {
    if (r.url().includes("/scene.glb")) glbAsked.push(r.url());
  });
  await page.getByTestId("download-button").click();
  await expect(page.getByTestId("download-no-glb")).toBeVisible();
  // Known from the revision's stages: no request, so no 404 in the console.
  expect(glbAsked).toEqual([]);
  await expect(page.getByTestId("download-glb")).toBeHidden();
  await expect(page.getByTestId("download-coco")).toBeVisible();
  await page.screenshot({
    path: screenshotPath("download-menu-no-glb.png"),
    clip: { x: 0, y: 0, width: 1440, height: 400 },
  });
  // A click elsewhere closes it too.
  await page.getByTestId("scene-title").click();
  await expect(page.getByTestId("download-menu")).not.toHaveAttribute("open");
});

test("the list downloads the selected scenes as one zip", async ({ page }) => {
  const placed = (await seedScene(page.request, T3D_5, "zip placed")).scene_id;
  const unplaced = await importUnplaced(page, "zip not placed");
  const other = await importUnplaced(page, "zip left out");
  await page.goto("/#/");
  await expect(page.getByTestId(`scene-row-${other}`)).toBeVisible();
  const button = page.getByTestId("download-selected");
  await expect(button).toBeDisabled();
  await page.getByTestId(`select-scene-${placed}`).check();
  await page.getByTestId(`select-scene-${unplaced}`).check();
  await expect(button).toHaveText("Download 2 selected scenes (zip)");
  await expect(page.getByTestId("select-all-scenes")).toHaveJSProperty("indeterminate", true);
  await page.screenshot({ path: screenshotPath("download-selected.png") });

  const [download] = await Promise.all([page.waitForEvent("download"), button.click()]);
  expect(download.suggestedFilename()).toBe("holiscene-2-scenes.zip");
  const files = readZip(await contents(download));
  const index = JSON.parse(files.get("index.json")?.toString() ?? "null") as {
    scenes: { folder: string; scene_id: string; has_glb: boolean }[];
  };
  // In the list's order: newest first.
  expect(index.scenes.map((s) => [s.scene_id, s.has_glb])).toEqual([
    [unplaced, false],
    [placed, true],
  ]);
  for (const entry of index.scenes) {
    const saved = (await getScene(page.request, entry.scene_id)).scene;
    const sceneJson = files.get(`${entry.folder}/scene.json`);
    expect(JSON.parse(sceneJson?.toString() ?? "null")).toEqual(saved);
    const coco = JSON.parse(files.get(`${entry.folder}/coco.json`)?.toString() ?? "null");
    expect((coco as CocoFile).annotations).toHaveLength(saved.objects.length);
    const photo = files.get(`${entry.folder}/${saved.image.file}`);
    expect(photo?.equals(readFileSync(path.join(T3D_5, "img.jpg")))).toBe(true);
  }
  const [unplacedEntry, placedEntry] = index.scenes;
  const glb = files.get(`${placedEntry?.folder}/scene.glb`);
  expect(glb?.subarray(0, 4).toString()).toBe("glTF");
  expect(files.has(`${unplacedEntry?.folder}/scene.glb`)).toBe(false);
  expect([...files.keys()].some((name) => name.includes(other))).toBe(false);

  // The zip as it came goes back in through "Import a dataset": this store has those very
  // scenes, so it adds no copies and links to them (into another store it makes a scene per
  // folder with the same labels: backend/tests/api/routes/test_archive_import.py).
  const zip = { name: "holiscene-2-scenes.zip", mimeType: "application/zip" };
  await importZip(page, { ...zip, buffer: await contents(download) });
  const summary = page.getByTestId("dataset-import-summary");
  await expect(summary).toContainText(
    "holiscene-2-scenes.zip: 0 photos imported, 2 skipped as already stored, 0 not imported.",
  );
  await page.getByText("Already stored (2)").click();
  const links = page.getByTestId("dataset-import-skipped").getByRole("link");
  await expect(links).toHaveCount(2);
  const targets = await links.evaluateAll((found) => found.map((a) => a.getAttribute("href")));
  expect(targets.sort()).toEqual(index.scenes.map((entry) => `#/scenes/${entry.scene_id}`).sort());
  // Named as the scenes are, the zip's folders beside them.
  expect((await links.allTextContents()).sort()).toEqual(["zip not placed", "zip placed"]);
  await expect(page.getByTestId("dataset-import-skipped")).toContainText(
    `from ${unplacedEntry?.folder}`,
  );

  // The same scenes as a COCO dataset, as `holiscene export --format coco` writes it.
  await page.getByTestId(`select-scene-${placed}`).check();
  await page.getByTestId(`select-scene-${unplaced}`).check();
  await page.getByTestId("download-format").selectOption({ label: "COCO dataset" });
  await expect(button).toHaveAttribute("title", /annotations\.json/);
  const [asCoco] = await Promise.all([page.waitForEvent("download"), button.click()]);
  expect(asCoco.suggestedFilename()).toBe("holiscene-2-scenes-coco.zip");
  const cocoFiles = readZip(await contents(asCoco));
  const dataset = JSON.parse(cocoFiles.get("annotations.json")?.toString() ?? "null") as CocoFile;
  expect(dataset.annotations.length).toBeGreaterThan(0);
  expect([...cocoFiles.keys()].filter((name) => name.startsWith("images/"))).toHaveLength(2);
  // A format with nothing to write says why, and nothing is downloaded.
  await page.getByTestId("download-format").selectOption({ label: "Support pairs" });
  await button.click();
  await expect(page.getByTestId("download-selected-status")).toContainText(
    "has supports set by a person: nothing to train on",
  );

  // "Select all" ticks every listed scene; unticking it clears them.
  await page.getByTestId("select-all-scenes").check();
  await expect(page.getByTestId(`select-scene-${other}`)).toBeChecked();
  await page.getByTestId("select-all-scenes").uncheck();
  await expect(button).toBeDisabled();
});
