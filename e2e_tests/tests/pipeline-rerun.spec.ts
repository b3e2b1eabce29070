// User story: an admin runs the pipeline again on a scene. An unsaved edit is saved first
// (the re-run keeps it). The scene stays on the page, read only and saying why, while the job
// runs (the progress bar names its stage), and the new revision replaces it when the job ends.
import { expect, test } from "@playwright/test";
import { getScene, seedScene, supportOf, T3D_5 } from "../helpers/api";
import { clickArrow, openScene } from "../helpers/photo";

test("running the pipeline again saves the unsaved edit, keeps the scene in view, read only, until the result", async ({
  page,
}) => {
  const doc = await seedScene(page.request, T3D_5, "run again");
  await openScene(page, doc.scene_id);
  // The job's answers come a second late, so the run is not over before the page is looked at.
  await page.route("**/api/jobs/*", async (route) => {
    await new Promise((resolve) => setTimeout(resolve, 1000));
    await route.continue();
  });
  // An edit not saved yet when the run is asked for: saved first, and kept by the run.
  await clickArrow(page, "o3");
  await page.keyboard.press("w");
  await expect(page.getByTestId("save-status")).toHaveAttribute("data-state", "dirty");
  // It asks first (the button is one click from Open in viser); a No runs nothing.
  let asked = "";
  page.once("dialog", (dialog) => {
    asked = dialog.message();
    void dialog.dismiss();
  });
  await page.getByTestId("run-pipeline").click();
  expect(asked).toContain("every label a person set is kept");
  await expect(page.getByTestId("run-pipeline")).toBeEnabled();
  await expect(page.getByTestId("job-progress")).toBeHidden();
  page.once("dialog", (dialog) => void dialog.accept());
  await page.getByTestId("run-pipeline").click();
  await expect(page.getByTestId("read-only-banner")).toContainText("Pipeline running — read only");
  await expect(page.getByTestId("photo")).toHaveAttribute("data-loaded", "true");
  await expect(page.getByTestId("object-table")).toBeVisible();
  await expect(page.locator("[data-testid^='supporter-select-']").first()).toBeDisabled();
  await expect(page.getByTestId("run-pipeline")).toBeDisabled();
  // The result: the next revision, editable again.
  await expect(page.getByTestId("scene-meta")).toContainText(`revision ${doc.revision + 2}`, {
    timeout: 60_000,
  });
  expect(supportOf(await getScene(page.request, doc.scene_id), "o3")).toMatchObject({
    parent: "wall",
    source: "manual",
  });
  await expect(page.getByTestId("arrow-o3")).toHaveAttribute("data-parent", "wall");
  await expect(page.getByTestId("recovery-banner")).toBeHidden();
  await expect(page.getByTestId("read-only-banner")).toBeHidden();
  await expect(page.locator("[data-testid^='supporter-select-']").first()).toBeEnabled();
  await expect(page.getByTestId("run-pipeline")).toBeEnabled();
});
