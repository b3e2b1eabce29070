// User story: an admin archives a junk scene. It leaves the scene list and turns read only
// (the banner says who archived it); the list's Archived filter shows it, and Unarchive brings
// it back as it was, editable again.
import type { SceneSummary } from "@holiscene/schema";
import { expect, test } from "@playwright/test";
import { seedScene, T3D_5 } from "../helpers/api";
import { openScene } from "../helpers/photo";
import { screenshotPath } from "../helpers/screenshots";

test("an admin archives a scene, finds it under Archived and restores it", async ({ page }) => {
  const doc = await seedScene(page.request, T3D_5, "archive me");
  await openScene(page, doc.scene_id);
  const archive = page.getByTestId("workflow-archive");
  const restore = page.getByTestId("workflow-unarchive");
  await expect(archive).toBeVisible();
  await expect(restore).toBeHidden();
  await expect(page.getByTestId("read-only-banner")).toBeHidden();

  // It asks first; then the scene is read only, saying why.
  let asked = "";
  page.once("dialog", (dialog) => {
    asked = dialog.message();
    void dialog.accept();
  });
  await archive.click();
  await expect(restore).toBeVisible();
  await expect(archive).toBeHidden();
  expect(asked).toContain('Archive "archive me"?');
  await expect(page.getByTestId("read-only-banner")).toContainText("archived by local");
  await expect(page.getByTestId("workflow-state")).toHaveText(/^archived · /);
  await expect(page.getByTestId("workflow-events").locator("li").last()).toContainText(
    "local archived it",
  );
  await expect(page.locator("[data-testid^='supporter-select-']").first()).toBeDisabled();
  await expect(page.getByTestId("run-pipeline")).toBeDisabled();
  // No workflow step is offered on it (taking it would only be refused).
  await expect(page.getByTestId("workflow-take")).toBeHidden();
  await page.screenshot({ path: screenshotPath("scene-archived.png"), fullPage: true });
  const listed = (await (await page.request.get("/api/scenes")).json()) as SceneSummary[];
  expect(listed.some((s) => s.id === doc.scene_id)).toBe(false);

  // Out of the list; the Archived filter shows it.
  await page.goto("/#/");
  const row = page.getByTestId(`scene-state-${doc.scene_id}`);
  await expect(page.getByTestId("state-filter")).toBeVisible();
  await expect(row).toHaveCount(0);
  await page.getByTestId("state-filter").selectOption("archived");
  await expect(row).toBeVisible();
  await expect(row).toHaveText(/^archived · /);
  // Opened from there, Back finds the list still filtered (kept for this tab).
  await page.getByTestId(`scene-row-${doc.scene_id}`).locator("a.scene-name-link").click();
  await expect(page.getByTestId("photo")).toHaveAttribute("data-loaded", "true");
  await page.goBack();
  await expect(page.getByTestId("state-filter")).toHaveValue("archived");
  await expect(row).toBeVisible();

  // Restored as it was: editable, and back in the list.
  await openScene(page, doc.scene_id);
  await restore.click();
  await expect(archive).toBeVisible();
  await expect(page.getByTestId("read-only-banner")).toBeHidden();
  await expect(page.locator("[data-testid^='supporter-select-']").first()).toBeEnabled();
  await expect(page.getByTestId("workflow-take")).toBeVisible();
  const back = (await (await page.request.get("/api/scenes")).json()) as SceneSummary[];
  expect(back.find((s) => s.id === doc.scene_id)?.revision).toBe(doc.revision);
});
