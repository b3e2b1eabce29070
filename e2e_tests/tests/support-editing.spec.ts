// User story: an annotator opens a scene, sees masks, support arrows and the 3D scene,
// corrects an object's supporter and support type, and the correction is saved.
import { mkdirSync } from "node:fs";
import path from "node:path";
import { expect, type Page, test } from "@playwright/test";
import { getRevisions, getScene, seedScene, supportOf, T3D_5 } from "../helpers/api";
import { canvasColours } from "../helpers/canvas";

const SCREENSHOTS = path.resolve(import.meta.dirname, "../screenshots");
mkdirSync(SCREENSHOTS, { recursive: true });

async function openScene(page: Page, sceneId: string): Promise<void> {
  await page.goto(`/#/scenes/${sceneId}`);
  await expect(page.getByTestId("object-table")).toBeVisible();
}

async function setAuthor(page: Page, name: string): Promise<void> {
  const input = page.getByTestId("author-input");
  await input.fill(name);
  await input.press("Tab");
}

test("shows masks, arrows and the 3D scene, and saves a changed supporter", async ({
  page,
  request,
}) => {
  const seeded = await seedScene(request, T3D_5, "t3d-5 editing");
  const objects = seeded.scene.objects ?? [];
  expect(objects.length).toBeGreaterThanOrEqual(3);
  const [parent, , child] = objects;
  if (!parent || !child) throw new Error("the seeded scene has too few objects");
  const before = supportOf(seeded, child.id);
  expect(before?.parent).not.toBe(parent.id);

  await openScene(page, seeded.scene_id);
  await setAuthor(page, "e2e-annotator");

  // One mask and one arrow per object.
  for (const object of objects) {
    await expect(page.getByTestId(`mask-${object.id}`)).toBeVisible();
    await expect(page.getByTestId(`arrow-${object.id}`)).toBeVisible();
  }
  await expect(page.getByTestId("arrow-layer").locator("[data-testid^='arrow-']")).toHaveCount(
    objects.length,
  );

  // Masks can be hidden and shown again.
  await page.getByTestId("toggle-masks").uncheck();
  await expect(page.getByTestId(`mask-${child.id}`)).toBeHidden();
  await page.getByTestId("toggle-masks").check();
  await expect(page.getByTestId(`mask-${child.id}`)).toBeVisible();

  // The 3D panel drew the scene: not one flat colour.
  const canvas = page.getByTestId("scene3d-canvas");
  await expect(canvas).toHaveAttribute("data-status", "ready", { timeout: 60_000 });
  const colours = await canvasColours(canvas);
  expect(colours.width).toBeGreaterThan(100);
  expect(colours.distinct).toBeGreaterThan(3);
  expect(colours.nonBackground).toBeGreaterThan(0.02);
  await canvas.screenshot({ path: path.join(SCREENSHOTS, "scene3d.png") });
  await page.screenshot({ path: path.join(SCREENSHOTS, "scene-page.png"), fullPage: true });

  // Hovering an object's row highlights its mask, and hovering the mask its row.
  await page.getByTestId(`object-row-${child.id}`).hover();
  await expect(page.getByTestId(`mask-${child.id}`)).toHaveClass(/is-hovered/);
  await page.getByTestId(`mask-${child.id}`).hover({ force: true });
  await expect(page.getByTestId(`object-row-${child.id}`)).toHaveClass(/is-hovered/);

  // Without a supporter the object is flagged and has no arrow.
  await page.getByTestId(`supporter-select-${child.id}`).selectOption("");
  await expect(page.getByTestId(`unsupported-${child.id}`)).toBeVisible();
  await expect(page.getByTestId(`arrow-${child.id}`)).toHaveCount(0);
  await expect(page.getByTestId(`object-row-${child.id}`)).toHaveAttribute(
    "data-unsupported",
    "true",
  );
  await expect(page.getByTestId("support-summary")).toContainText("1 without a supporter");

  // Change the child's supporter and type; the arrow follows at once, marked unsaved.
  await page.getByTestId(`supporter-select-${child.id}`).selectOption(parent.id);
  await page.getByTestId(`type-select-${child.id}`).selectOption("behind");
  const arrow = page.getByTestId(`arrow-${child.id}`);
  await expect(arrow).toHaveAttribute("data-parent", parent.id);
  await expect(arrow).toHaveAttribute("data-type", "behind");
  await expect(arrow).toHaveAttribute("data-pending", "true");
  await expect(page.getByTestId("save-status")).toHaveAttribute("data-state", "dirty");

  await page.getByTestId("save-button").click();
  const status = page.getByTestId("save-status");
  await expect(status).toHaveAttribute("data-state", "saved");
  await expect(status).toHaveText(/^Saved/);
  await page.screenshot({ path: path.join(SCREENSHOTS, "saved.png"), fullPage: true });

  // Reloaded, the page shows the saved change.
  await page.reload();
  await expect(page.getByTestId(`supporter-select-${child.id}`)).toHaveValue(parent.id);
  await expect(page.getByTestId(`type-select-${child.id}`)).toHaveValue("behind");
  await expect(arrow).toHaveAttribute("data-parent", parent.id);
  await expect(arrow).toHaveAttribute("data-pending", "false");
  await expect(arrow).toHaveClass(/arrow--behind/);
  await expect(page.getByTestId("author-input")).toHaveValue("e2e-annotator");

  // The server has a new revision with a manual support by this author.
  const doc = await getScene(request, seeded.scene_id);
  expect(doc.revision).toBe(seeded.revision + 1);
  expect(supportOf(doc, child.id)).toMatchObject({
    parent: parent.id,
    type: "behind",
    source: "manual",
    author: "e2e-annotator",
  });
  const revisions = await getRevisions(request, seeded.scene_id);
  expect(revisions.at(-1)).toMatchObject({
    number: doc.revision,
    kind: "edit",
    author: "e2e-annotator",
  });
});

test("a save based on a stale revision shows a conflict and keeps the edit", async ({
  context,
  request,
}) => {
  const seeded = await seedScene(request, T3D_5, "t3d-5 conflict");
  const [first, second, , fourth] = seeded.scene.objects ?? [];
  if (!first || !second || !fourth) throw new Error("the seeded scene has too few objects");

  // Two annotators open the same revision.
  const alice = await context.newPage();
  const bob = await context.newPage();
  await openScene(alice, seeded.scene_id);
  await openScene(bob, seeded.scene_id);

  await alice.getByTestId(`supporter-select-${second.id}`).selectOption(first.id);
  await alice.getByTestId("save-button").click();
  await expect(alice.getByTestId("save-status")).toHaveAttribute("data-state", "saved");

  // Bob saves on the revision he loaded, which is no longer the latest.
  await bob.getByTestId(`type-select-${fourth.id}`).selectOption("behind");
  await bob.getByTestId("save-button").click();
  const conflict = bob.getByTestId("conflict-message");
  await expect(conflict).toBeVisible();
  await expect(conflict).toContainText("not saved");
  await expect(bob.getByTestId("save-status")).toHaveAttribute("data-state", "conflict");
  // His edit is still there, visibly unsaved.
  await expect(bob.getByTestId(`type-select-${fourth.id}`)).toHaveValue("behind");
  await expect(bob.getByTestId(`arrow-${fourth.id}`)).toHaveAttribute("data-pending", "true");
  await expect(bob.getByTestId("pending-edits")).toContainText(fourth.id);
  await bob.screenshot({ path: path.join(SCREENSHOTS, "conflict.png"), fullPage: true });

  // Reload: Alice's change appears, Bob's edit is re-applied on top, and saves.
  await bob.getByTestId("conflict-reload").click();
  await expect(conflict).toBeHidden();
  await expect(bob.getByTestId("reload-notice")).toBeVisible();
  await expect(bob.getByTestId(`supporter-select-${second.id}`)).toHaveValue(first.id);
  await expect(bob.getByTestId(`type-select-${fourth.id}`)).toHaveValue("behind");
  await expect(bob.getByTestId("save-status")).toHaveAttribute("data-state", "dirty");
  await bob.getByTestId("save-button").click();
  await expect(bob.getByTestId("save-status")).toHaveAttribute("data-state", "saved");

  const doc = await getScene(request, seeded.scene_id);
  expect(doc.revision).toBe(seeded.revision + 2);
  expect(supportOf(doc, second.id)).toMatchObject({ parent: first.id, source: "manual" });
  expect(supportOf(doc, fourth.id)).toMatchObject({ type: "behind", source: "manual" });
});
