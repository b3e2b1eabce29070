// User story: on a photo without objects an annotator draws boxes with the box tool, names
// each with the class picker (typing part of a name, or an alias), and gives it a supporter;
// the server cuts each object's mask. Moving a box with its handle is one more saved edit.
// After a reload everything is there: objects, classes, boxes, masks and supports.
import { expect, test } from "@playwright/test";
import { getScene, importWithoutObjects, supportOf } from "../helpers/api";
import {
  chooseTool,
  dragOnPhoto,
  objectEditsSaved,
  pickClass,
  screenPoint,
} from "../helpers/objects";
import { screenshotPath } from "../helpers/screenshots";

test("boxes drawn on an empty photo become objects with masks and supporters", async ({ page }) => {
  const sceneId = await importWithoutObjects(page.request, "t3d-5 box tool");
  await page.goto(`/#/scenes/${sceneId}`);
  await expect(page.getByTestId("photo")).toHaveAttribute("data-loaded", "true");

  // The box tool by its key; a drag where there is no object draws a box.
  await page.keyboard.press("b");
  await expect(page.getByTestId("photo-tool-box")).toHaveAttribute("aria-pressed", "true");
  // Escape gives the tool back (the page's own Escape, clearing the selection, must not win).
  await page.keyboard.press("Escape");
  await expect(page.getByTestId("photo-tool-select")).toHaveAttribute("aria-pressed", "true");
  await page.keyboard.press("b");
  const a = await screenPoint(page, 150, 190);
  const b = await screenPoint(page, 625, 525);
  await page.mouse.move(a.x, a.y);
  await page.mouse.down();
  await page.mouse.move(b.x, b.y, { steps: 5 });
  await expect(page.getByTestId("box-tool-drawing")).toHaveCount(1);
  await page.mouse.up();
  // The picker opens beside the box. Enter on a blank field picks nothing (the first line
  // would be a guess nobody chose): it says how to choose.
  await expect(page.getByTestId("class-picker")).toBeVisible();
  await page.getByTestId("class-picker-input").fill("  ");
  await page.keyboard.press("Enter");
  await expect(page.getByTestId("class-picker")).toBeVisible();
  await expect(page.getByTestId("class-picker-hint")).toHaveText(/^Type a class/);
  await expect(page.locator('.masks [data-object="d1"]')).toHaveCount(0);
  // Type part of the name.
  await page.getByTestId("class-picker-input").fill("be");
  await page.screenshot({ path: screenshotPath("box-tool-class-picker.png") });
  // 1 picks the first line.
  await expect(page.getByTestId("class-option").first()).toHaveAttribute("data-name", "bed");
  await page.keyboard.press("1");
  await expect(page.getByTestId("class-picker")).toHaveCount(0);
  await expect(page.locator('.masks [data-object="d1"]')).toHaveCount(1);
  await objectEditsSaved(page);
  await expect(page.getByTestId("object-edit-status")).toContainText(": saved.");
  // The line is on the dark band over the photo's top edge, the photo's width: it moves
  // nothing and has room for what to do next (beside the tool buttons it had 200 pixels).
  const line = await page.getByTestId("object-edit-status").boundingBox();
  const image = await page.getByTestId("photo-image").boundingBox();
  const frame = await page.getByTestId("photo").boundingBox();
  if (!line || !image || !frame) throw new Error("the status line or the photo is not shown");
  expect(line.y).toBeGreaterThanOrEqual(frame.y);
  expect(line.y + line.height).toBeLessThanOrEqual(image.y);
  expect(line.width).toBeGreaterThan(frame.width * 0.9);

  // The new object is selected: the floor holds it up (F).
  await expect(page.getByTestId("box-tool-selected")).toHaveCount(1);
  await page.keyboard.press("f");

  // Zoom in on the night stand with the wheel (about the pointer), and draw it there, named
  // by an alias: "nightstand" is stored as night_stand.
  const photo = page.getByTestId("photo");
  const standCentre = await screenPoint(page, 75, 366);
  await page.mouse.move(standCentre.x, standCentre.y);
  await page.mouse.wheel(0, -200);
  await expect.poll(async () => Number(await photo.getAttribute("data-zoom"))).toBeGreaterThan(1.2);
  await expect(page.getByTestId("photo-zoom-level")).toHaveText(/^1\d\d%$/);
  const after = await screenPoint(page, 75, 366);
  expect(Math.hypot(after.x - standCentre.x, after.y - standCentre.y)).toBeLessThan(2);
  await dragOnPhoto(page, [3, 288], [148, 445]);
  await pickClass(page, "nightstand", "nightstand");
  await expect(page.locator('.masks [data-object="d2"]')).toHaveCount(1);
  await page.keyboard.press("f");

  // Resize the night stand with its right handle (it is selected, handles shown at their
  // screen size whatever the zoom).
  await expect(page.getByTestId("box-handle")).toHaveCount(8);
  // Polled: the revision the class pick saves redraws the handles, and a handle being
  // redrawn has no box for a moment.
  const handleWidth = async () =>
    (await page.locator('[data-handle="e"]').boundingBox())?.width ?? 0;
  await expect.poll(handleWidth).toBeGreaterThan(7);
  expect(await handleWidth()).toBeLessThan(12);
  await page.screenshot({ path: screenshotPath("box-tool-handles.png") });
  await dragOnPhoto(page, [148, 366.5], [156, 366.5]);
  await objectEditsSaved(page);
  // 0 fits the whole photo again.
  await page.keyboard.press("0");
  await expect(photo).toHaveAttribute("data-zoom", "1.000");
  await expect(page.getByTestId("photo-zoom-fit")).toBeHidden();
  await expect(page.getByTestId("save-status")).toHaveAttribute("data-state", /saved|clean/, {
    timeout: 15_000,
  });

  const doc = await getScene(page.request, sceneId);
  const objects = doc.scene.objects ?? [];
  const bed = objects.find((o) => o.id === "d1");
  const stand = objects.find((o) => o.id === "d2");
  expect(bed?.class).toBe("bed");
  expect(bed?.source).toBe("manual");
  expect(bed?.mask?.rle.length ?? 0).toBeGreaterThan(1);
  expect(bed?.bbox[0]).toBeCloseTo(150, 0);
  expect(stand?.class).toBe("night_stand");
  expect(stand?.bbox[2]).toBeCloseTo(156, 0);
  expect(stand?.mask?.rle.length ?? 0).toBeGreaterThan(1);
  expect(supportOf(doc, "d1")?.parent).toBe("floor");
  expect(supportOf(doc, "d2")?.parent).toBe("floor");

  // A reload keeps everything.
  await page.reload();
  await expect(page.getByTestId("photo")).toHaveAttribute("data-loaded", "true");
  await expect(page.locator('.masks [data-object="d1"]')).toHaveCount(1);
  await expect(page.locator('.masks [data-object="d2"]')).toHaveCount(1);
  await expect(page.locator('tr[data-object="d2"]')).toBeVisible();
  const again = await getScene(page.request, sceneId);
  expect(again.revision).toBe(doc.revision);
  expect(again.scene.objects).toEqual(doc.scene.objects);
  expect(again.scene.supports).toEqual(doc.scene.supports);
  await chooseTool(page, "select");
});

test("a box whose answer never arrived is saved once: sent again by itself, it finds itself saved", async ({
  page,
}) => {
  const sceneId = await importWithoutObjects(page.request, "t3d-5 lost answer");
  await page.goto(`/#/scenes/${sceneId}`);
  await expect(page.getByTestId("photo")).toHaveAttribute("data-loaded", "true");
  const before = (await getScene(page.request, sceneId)).revision;
  // The first save reaches the server, which stores it; its answer is lost on the way back.
  let sent = 0;
  await page.route("**/api/scenes/*/edits", async (route) => {
    sent += 1;
    if (sent > 1) return route.continue();
    await route.fetch();
    return route.abort("failed");
  });
  await page.keyboard.press("b");
  await dragOnPhoto(page, [150, 190], [625, 525]);
  await pickClass(page, "bed", "bed");
  await expect(page.getByTestId("object-edit-failure")).toBeVisible();
  expect((await getScene(page.request, sceneId)).scene.objects?.map((o) => o.id)).toEqual(["d1"]);
  // The list points at the retry, not at adding the objects again.
  await expect(page.getByTestId("support-summary")).toContainText('"add bed d1" has no answer');

  await expect(page.getByTestId("object-edit-failure-text")).toContainText(
    "Trying again every few seconds",
  );
  // Sent again a few seconds later, it meets the revision it made itself: nothing is added twice.
  await expect(page.getByTestId("object-edit-status")).toContainText(
    `already saved as revision ${before + 1}`,
    { timeout: 20_000 },
  );
  await expect(page.getByTestId("object-edit-failure")).toBeHidden();
  await objectEditsSaved(page);
  expect(sent).toBe(2);
  const saved = await getScene(page.request, sceneId);
  expect(saved.revision).toBe(before + 1);
  expect(saved.scene.objects?.map((o) => [o.id, o.class])).toEqual([["d1", "bed"]]);
  await expect(page.locator(".masks [data-object]")).toHaveCount(1);
  // Undo takes the object back out, as for any add.
  await page.keyboard.press("Escape");
  await page.keyboard.press("Control+z");
  await expect.poll(async () => (await getScene(page.request, sceneId)).revision).toBe(before + 2);
  expect((await getScene(page.request, sceneId)).scene.objects ?? []).toEqual([]);
});

test("a box whose class was still being picked when the page was left is offered on the next visit", async ({
  page,
}) => {
  const sceneId = await importWithoutObjects(page.request, "t3d-5 box left unnamed");
  await page.goto("/#/");
  await page.goto(`/#/scenes/${sceneId}`);
  await expect(page.getByTestId("photo")).toHaveAttribute("data-loaded", "true");
  await page.keyboard.press("b");
  await dragOnPhoto(page, [150, 190], [400, 420]);
  await expect(page.getByTestId("class-picker")).toBeVisible();
  await page.getByTestId("class-picker-input").fill("lamp");
  // The browser's Back, the picker still open: the picker goes with the page.
  await page.goBack();
  await expect(page.getByTestId("scene-list")).toBeVisible();
  await expect(page.getByTestId("class-picker")).toHaveCount(0);
  expect((await getScene(page.request, sceneId)).scene.objects ?? []).toHaveLength(0);

  // Back on the scene: the box is offered, and Retry adds it (as otherprop) and asks its
  // class again, the new object selected.
  await page.goto(`/#/scenes/${sceneId}`);
  await expect(page.getByTestId("photo")).toHaveAttribute("data-loaded", "true");
  const failureText = page.getByTestId("object-edit-failure-text");
  await expect(failureText).toContainText("Not saved on your last visit");
  await expect(failureText).toContainText("asks its class again");
  await page.getByTestId("object-edit-retry").click();
  await expect(page.getByTestId("class-picker")).toBeVisible();
  const added = (await getScene(page.request, sceneId)).scene.objects ?? [];
  expect(added.map((o) => o.class)).toEqual(["otherprop"]);
  const [x1 = 0, y1 = 0, x2 = 0, y2 = 0] = added[0]?.bbox ?? [];
  expect([x1, y1, x2, y2].map((v) => Math.round(v / 10))).toEqual([15, 19, 40, 42]);
  await expect(page.getByTestId(`object-row-${added[0]?.id}`)).toHaveClass(/is-selected/);
  await page.getByTestId("class-picker-input").fill("lamp");
  await page.keyboard.press("Enter");
  await objectEditsSaved(page);
  const named = (await getScene(page.request, sceneId)).scene.objects ?? [];
  expect(named.map((o) => [o.id, o.class])).toEqual([[added[0]?.id, "lamp"]]);
});
