// User story: a reviewer looks at the reconstruction in the page's 3D view: the room, the
// objects, the photo's camera frustum with the photo on it and the support arrows; orbits;
// picks objects there or on the photo and sees them selected in both; exports a PNG.
import { readFileSync } from "node:fs";
import { expect, test } from "@playwright/test";
import { T3D_5 } from "../helpers/api";
import { canvasColours } from "../helpers/canvas";
import { nextFrames, openScene, scene3d, seedFolder } from "../helpers/scene3d";
import { screenshotPath } from "../helpers/screenshots";

const PNG_SIGNATURE = [0x89, 0x50, 0x4e, 0x47, 0x0d, 0x0a, 0x1a, 0x0a];

test("shows the frustum and arrows, shares the selection with the photo, exports a PNG", async ({
  page,
  request,
}) => {
  test.setTimeout(300_000);
  const doc = await seedFolder(request, T3D_5, "t3d-5 3d view");
  const objects = doc.scene.objects ?? [];
  const supports = doc.scene.supports ?? [];
  expect(objects.length).toBeGreaterThanOrEqual(3);
  await openScene(page, doc.scene_id);
  const canvas = page.getByTestId("scene3d-canvas");

  // The photo's camera: a frustum turned by the stored pitch and roll, the photo on it.
  expect(await scene3d(page, (p) => p.frustumShown())).toBe(true);
  await expect.poll(() => scene3d(page, (p) => p.photoOnFrustum()), { timeout: 30_000 }).toBe(true);
  const pose = await scene3d(page, (p) => p.cameraPose());
  expect(pose?.pitchDeg).toBeCloseTo(doc.scene.camera?.pitch_deg ?? Number.NaN, 6);
  expect(pose?.rollDeg).toBeCloseTo(doc.scene.camera?.roll_deg ?? Number.NaN, 6);
  // The room from the layout, and one arrow per support, typed as saved.
  const room = await scene3d(page, (p) => p.roomCorners());
  const stored = doc.scene.layout?.corners_3d ?? [];
  for (const [i, corner] of (room ?? []).entries()) {
    for (const [j, v] of corner.entries()) expect(v).toBeCloseTo(stored[i]?.[j] ?? Number.NaN, 3);
  }
  const arrows = await scene3d(page, (p) => p.arrows());
  const key = (s: { child: string; parent: string; type: string }) =>
    `${s.child}<${s.parent}:${s.type}`;
  expect(arrows.map(key).sort()).toEqual(supports.map(key).sort());

  await nextFrames(page);
  // On a loaded machine the first frames after a resize can still be blank: wait for a drawn
  // one (a view that never draws still fails).
  await expect
    .poll(async () => (await canvasColours(canvas)).distinct, { timeout: 15_000 })
    .toBeGreaterThan(8);
  await canvas.screenshot({ path: screenshotPath("scene3d-frustum-arrows.png") });

  // Orbit with the mouse: the view changes.
  const before = await canvas.screenshot();
  const box = await canvas.boundingBox();
  if (!box) throw new Error("the 3D canvas is not laid out");
  await page.mouse.move(box.x + box.width * 0.5, box.y + box.height * 0.5);
  await page.mouse.down();
  await page.mouse.move(box.x + box.width * 0.7, box.y + box.height * 0.45, { steps: 8 });
  await page.mouse.up();
  await nextFrames(page);
  expect((await canvas.screenshot()).equals(before)).toBe(false);
  await page.getByTestId("scene3d-overview").click();

  // Clicking an object in 3D selects it on the photo too.
  const [first, second] = [objects[0]?.id ?? "", objects[2]?.id ?? ""];
  const at = await scene3d(page, (p, id) => p.screenPointOf(id), first);
  if (!at) throw new Error(`object ${first} cannot be clicked in the 3D view`);
  const colour = (id: string) => scene3d(page, (p, i) => p.objectColour(i), id);
  const brightness = (rgb: number[] | null) => (rgb ?? []).reduce((sum, v) => sum + v, 0);
  await page.mouse.move(4, 4); // nothing hovered
  const plain = await colour(first);
  await page.mouse.click(at.x, at.y);
  await expect(canvas).toHaveAttribute("data-selected", first);
  await expect(page.getByTestId(`mask-${first}`)).toHaveClass(/is-selected/);
  // As on the photo, a second click on it deselects it; a third selects it again.
  await page.mouse.click(at.x, at.y);
  await expect(canvas).toHaveAttribute("data-selected", "");
  await page.mouse.click(at.x, at.y);
  await expect(canvas).toHaveAttribute("data-selected", first);
  // The object pointed at is named over the view, with its 3D box's size in metres.
  const caption = page.getByTestId("scene3d-caption");
  await expect(caption).toContainText(
    new RegExp(`^${first} .* · 3D box [0-9.]+ × [0-9.]+ × [0-9.]+ m`),
  );
  // The selected object glows in 3D, on top of its class colour.
  await page.mouse.move(4, 4);
  expect(brightness(await colour(first))).toBeGreaterThan(brightness(plain) + 0.1);
  // Its id is over it, as on the photo, marked as selected; other objects' ids too, and a click
  // on one selects that object.
  const label = (id: string) => page.getByTestId(`scene3d-label-${id}`);
  await expect(label(first)).toBeVisible();
  await expect(label(first)).toHaveClass(/is-selected/);
  const tagged = await page
    .locator('[data-testid^="scene3d-label-"]:visible')
    .evaluateAll((tags) => tags.map((t) => (t as HTMLElement).dataset.object ?? ""));
  expect(tagged.length).toBeGreaterThanOrEqual(Math.min(3, objects.length));
  const other = tagged.find((id) => id !== first) ?? "";
  await label(other).click();
  await expect(canvas).toHaveAttribute("data-selected", other);
  await expect(label(first)).not.toHaveClass(/is-selected/);
  await page.getByTestId("toggle-scene3d-labels").uncheck();
  await expect(label(other)).toBeHidden();
  await page.getByTestId("toggle-scene3d-labels").check();
  await expect(label(other)).toBeVisible();
  await canvas.click({ position: { x: 4, y: 4 } });
  await page.mouse.move(4, 4);

  // A click on nothing in 3D clears it; a click on the photo selects there and in 3D.
  await canvas.click({ position: { x: 4, y: 4 } });
  await expect(canvas).toHaveAttribute("data-selected", "");
  await expect(caption).toBeHidden();
  await expect(page.getByTestId(`mask-${first}`)).not.toHaveClass(/is-selected/);
  expect(await colour(first)).toEqual(plain);
  await page.getByTestId("toggle-arrows").uncheck();
  await page.getByTestId("toggle-labels").uncheck();
  await page.getByTestId(`mask-${second}`).click({ force: true });
  await expect(page.getByTestId(`mask-${second}`)).toHaveClass(/is-selected/);
  await expect(canvas).toHaveAttribute("data-selected", second);
  await page.screenshot({ path: screenshotPath("scene3d-selection.png"), fullPage: true });

  // Export PNG downloads the view as a PNG file of the canvas's size.
  const downloading = page.waitForEvent("download");
  await page.getByTestId("scene3d-export").click();
  const download = await downloading;
  expect(download.suggestedFilename()).toMatch(/-r\d+-3d\.png$/);
  const file = await download.path();
  const bytes = readFileSync(file);
  expect([...bytes.subarray(0, 8)]).toEqual(PNG_SIGNATURE);
  expect(bytes.subarray(12, 16).toString("latin1")).toBe("IHDR");
  const size = await canvas.evaluate((c) => [
    (c as HTMLCanvasElement).width,
    (c as HTMLCanvasElement).height,
  ]);
  expect([bytes.readUInt32BE(16), bytes.readUInt32BE(20)]).toEqual(size);
  expect(bytes.length).toBeGreaterThan(20_000); // a picture, not a blank
  console.log(
    `Export PNG: ${download.suggestedFilename()}, ${size.join("x")}, ${bytes.length} bytes`,
  );
});
