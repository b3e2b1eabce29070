// User story: someone with a depth camera imports a photo with its depth through the form,
// sees on the scene page that the scene has depth, and lays the depth over the photo to check
// that the two are registered; depth that cannot be the photo's is refused with the reason.
import { execFileSync } from "node:child_process";
import { mkdirSync } from "node:fs";
import path from "node:path";
import { expect, test } from "@playwright/test";
import { fillUploadWithDepth, submitUploadAndWait } from "../helpers/photo";
import { synthesizeFolder } from "../helpers/synthetic";

const PYTHON = path.resolve(import.meta.dirname, "../../.venv/bin/python");
const SEED = 14; // a synthetic room with its rendered depth.png (16-bit millimetres)

test("a photo imported with its depth shows the depth over the photo", async ({ page }) => {
  const dir = synthesizeFolder(SEED);
  await page.goto("/#/");
  await fillUploadWithDepth(page, dir, "room with depth");
  const screenshots = path.resolve(import.meta.dirname, "../screenshots");
  mkdirSync(screenshots, { recursive: true });
  await page
    .getByTestId("upload-form")
    .screenshot({ path: path.join(screenshots, "upload-depth.png") });
  await submitUploadAndWait(page);

  await page.getByTestId("upload-open").click();
  await expect(page.getByTestId("scene-title")).toHaveText("room with depth");
  await expect(page.getByTestId("scene-meta")).toContainText("with depth");
  const layer = page.getByTestId("depth-layer");
  await expect(layer).toBeHidden();
  const toggle = page.getByTestId("toggle-depth");
  await expect(toggle).not.toBeChecked();
  await toggle.check();
  await expect(layer).toBeVisible();
  // The preview is a picture of the photo's size that the browser decoded.
  const size = await page.evaluate(async () => {
    const image = document.querySelector("[data-testid='depth-image']");
    const href = image?.getAttribute("href");
    if (!href) return null;
    const bitmap = await createImageBitmap(await (await fetch(href)).blob());
    return [bitmap.width, bitmap.height];
  });
  expect(size).toEqual([640, 480]);
  await page
    .getByTestId("photo")
    .screenshot({ path: path.join(screenshots, "depth-over-photo.png") });
  await toggle.uncheck();
  await expect(layer).toBeHidden();
});

test("depth of another size is refused by the form with the reason", async ({ page }, testInfo) => {
  const dir = synthesizeFolder(SEED);
  // 16-bit millimetres at a sensor's own resolution, not registered to the 640x480 photo.
  const small = testInfo.outputPath("small-depth.png");
  mkdirSync(path.dirname(small), { recursive: true });
  execFileSync(PYTHON, [
    "-c",
    "import sys, cv2, numpy as np; cv2.imwrite(sys.argv[1], np.full((48, 64), 2000, np.uint16))",
    small,
  ]);
  await page.goto("/#/");
  await page.getByTestId("upload-image").setInputFiles(path.join(dir, "img.png"));
  await page.getByTestId("upload-depth").setInputFiles(small);
  await page.getByTestId("upload-name").fill("refused depth");
  await page.getByTestId("upload-submit").click();
  await expect(page.getByTestId("upload-result")).toContainText(
    "Import failed: the depth file is 64x48 pixels, the photo is 640x480",
  );
  await expect(page.getByTestId("scene-list")).not.toContainText("refused depth");
});
