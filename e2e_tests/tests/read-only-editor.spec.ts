// User story: an annotator has an unsaved correction open while the scene gets submitted
// elsewhere (another tab). Saving is refused: the page shows the server's reason, keeps the
// correction (on the page and in this browser), and turns read only with a banner saying why.
// Once a reviewer sends the scene back, the next visit offers the kept correction, which is
// then saved: no work is lost. Local single-user mode (the one person may review too).
import type { SceneDocument } from "@holiscene/schema";
import { type Dialog, expect, type Page, test } from "@playwright/test";
import { getScene, seedScene, T3D_5 } from "../helpers/api";
import { keptDraft } from "../helpers/drafts";
import { chooseTool } from "../helpers/objects";
import { openScene, slowAutosave } from "../helpers/photo";
import { seedFolder, synthesize } from "../helpers/scene3d";
import { screenshotPath } from "../helpers/screenshots";

test("a save refused by the workflow lock keeps the edit, shows why, and is saved once the scene is sent back", async ({
  page,
  request,
}) => {
  test.setTimeout(300_000);
  const doc = await seedFolder(request, synthesize(14), "synth-14 lock");
  const id = doc.scene_id;
  await slowAutosave(page); // the save is the user's (Ctrl+S), at a known moment
  await openScene(page, id);
  await expect(page.getByTestId("read-only-banner")).toBeHidden();

  // A correction in the page, not saved yet.
  const support = (doc.scene.supports ?? [])[0];
  if (!support) throw new Error("the scene has no supports");
  const target = support.parent === "floor" ? "wall" : "floor";
  const select = page.getByTestId(`supporter-select-${support.child}`);
  await select.selectOption(target);
  await expect(page.getByTestId("pending-edits")).toContainText(support.child);

  // Meanwhile, elsewhere, the scene is taken and submitted.
  expect((await request.post(`/api/scenes/${id}/take`)).status()).toBe(200);
  const submitted = await request.post(`/api/scenes/${id}/submit`, {
    data: { revision: doc.revision },
  });
  expect(submitted.status(), await submitted.text()).toBe(200);

  // Saving is refused: the server's reason shows, the correction stays, the page is read only.
  await page.locator("body").click({ position: { x: 5, y: 5 } });
  await page.keyboard.press("Control+s");
  await expect(page.getByTestId("save-status")).toHaveText("Not saved: refused");
  await expect(page.getByTestId("save-error")).toContainText("submitted for review");
  await expect(page.getByTestId("read-only-reason")).toHaveText("Submitted for review — read only");
  await expect(page.getByTestId("read-only-banner")).toContainText(
    "Your 1 unsaved change is kept in this browser",
  );
  await expect(page.getByTestId("pending-edits")).toContainText(support.child);
  await expect(select).toHaveValue(target);
  await expect(select).toBeDisabled();
  await expect(page.getByTestId("layout-toggle")).toBeDisabled();
  // Greyed controls say why they are off, not what they would do.
  for (const testid of ["layout-toggle", "layout-reset", "replace-objects", "photo-tool-brush"]) {
    await expect(page.getByTestId(testid)).toHaveAttribute(
      "title",
      /^Not available now\. Submitted for review/,
    );
  }
  await expect(page.getByTestId("photo-tool-select")).toHaveAttribute("title", /^Select:/);
  // Its hint offers no edit it cannot make; an editing tool's key says why nothing happens.
  await expect(page.getByTestId("photo-tool-options")).toHaveText(/see where its labels came/);
  await page.locator("body").click({ position: { x: 5, y: 5 } });
  await page.keyboard.press("p");
  await expect(page.getByTestId("edit-message")).toContainText("Brush: Submitted for review");
  const kept = await keptDraft(page, id);
  expect(JSON.parse(kept || "{}").edits).toEqual([
    expect.objectContaining({ child: support.child, parent: target }),
  ]);
  expect((await getScene(request, id)).revision).toBe(doc.revision);
  await page.screenshot({ path: screenshotPath("read-only-refused.png"), fullPage: true });

  // The reviewer sends it back; the next visit offers the kept correction, and it is saved.
  const rejected = await request.post(`/api/scenes/${id}/reject`, {
    data: { revision: doc.revision, comment: "Check the supports again." },
  });
  expect(rejected.status(), await rejected.text()).toBe(200);
  await page.reload();
  await expect(page.getByTestId("object-table")).toBeVisible();
  await expect(page.getByTestId("workflow-state")).toHaveText("rejected");
  await expect(page.getByTestId("read-only-banner")).toBeHidden();
  await expect(page.getByTestId("recovery-text")).toContainText(support.child);
  await page.getByTestId("recovery-restore").click();
  await expect(select).toHaveValue(target);
  await expect(select).toBeEnabled();
  await expect(page.getByTestId("photo-tool-brush")).toHaveAttribute("title", /^Brush:/);
  await expect(page.getByTestId("photo-tool-options")).toHaveText(/drag an arrow's head/);
  await expect(page.getByTestId("layout-toggle")).toHaveAttribute("title", /^Drag the room's/);
  await page.locator("body").click({ position: { x: 5, y: 5 } });
  await page.keyboard.press("Control+s");
  await expect(page.getByTestId("save-status")).toHaveAttribute("data-state", "saved");
  const saved: SceneDocument = await getScene(request, id);
  expect(saved.revision).toBe(doc.revision + 1);
  expect(saved.scene.supports?.find((s) => s.child === support.child)).toMatchObject({
    parent: target,
    source: "manual",
  });
  await expect(page.getByTestId("workflow-state")).toHaveText("in annotation");

  // Submitting with an object left without a supporter asks first; saying no submits nothing.
  await select.selectOption("");
  await page.locator("body").click({ position: { x: 5, y: 5 } });
  await page.keyboard.press("Control+s");
  await expect(page.getByTestId("save-status")).toHaveAttribute("data-state", "saved");
  let asked = "";
  page.once("dialog", (dialog) => {
    asked = dialog.message();
    void dialog.dismiss();
  });
  await page.getByTestId("workflow-submit").click();
  await expect.poll(() => asked).toContain(`(${support.child}) has no supporter`);
  await expect(page.getByTestId("workflow-state")).toHaveText("in annotation");
  const workflow = await (await request.get(`/api/scenes/${id}/workflow`)).json();
  expect(workflow.state).toBe("in_annotation");
});

/** Submit the scene from the workflow bar, then send it back with a comment (one person
 * reviews). A question before submitting (none of the supporters set by a person) is
 * answered yes; returns what it asked ("" when nothing). */
async function submitAndSendBack(
  page: Page,
  comment: string,
  between?: () => Promise<void>,
): Promise<string> {
  let asked = "";
  const answer = (dialog: Dialog) => {
    asked = dialog.message();
    void dialog.accept();
  };
  page.once("dialog", answer);
  await page.getByTestId("workflow-submit").click();
  await expect(page.getByTestId("workflow-state")).toHaveText("submitted");
  page.off("dialog", answer);
  await between?.();
  await page.getByTestId("workflow-reject").click();
  await page.getByTestId("reject-comment").fill(comment);
  await page.getByTestId("reject-send").click();
  await expect(page.getByTestId("workflow-state")).toHaveText("rejected");
  return asked;
}

test("the editing tool a lock took away comes back when the scene is editable again", async ({
  page,
  request,
}) => {
  const seeded = await seedScene(request, T3D_5, "t3d-5 tool after lock");
  const id = seeded.scene_id;
  expect((await request.post(`/api/scenes/${id}/take`)).status()).toBe(200);
  await openScene(page, id);
  await chooseTool(page, "box");

  // Submitted, it is read only: the Box tool gives way to Select and cannot be chosen. Sent
  // back (here by the same person, who reviews too), the Box tool is in hand again.
  const asked = await submitAndSendBack(page, "Check the lamp's box.", async () => {
    await expect(page.getByTestId("photo-tool-select")).toHaveAttribute("aria-pressed", "true");
    await expect(page.getByTestId("photo-tool-box")).toBeDisabled();
    // Read only while submitted: the tool row, the detector bar and the layout buttons are
    // left out, not greyed.
    await expect(page.getByTestId("photo-tool-box")).toBeHidden();
    await expect(page.getByTestId("photo-tool-select")).toBeHidden();
    await expect(page.getByTestId("detector-bar")).toBeHidden();
    await expect(page.getByTestId("layout-toggle")).toBeHidden();
    await expect(page.getByTestId("layout-status")).toBeVisible();
  });
  await expect(page.getByTestId("layout-toggle")).toBeVisible();
  // Nobody set a supporter here: submitting asked first.
  expect(asked).toMatch(/None of the \d+ objects has a supporter set by a person/);
  await expect(page.getByTestId("photo-tool-box")).toHaveAttribute("aria-pressed", "true");

  // A tool chosen while locked is the person's choice: the next unlock leaves it.
  await page.getByTestId("workflow-take").click(); // "Reopen for changes"
  await expect(page.getByTestId("workflow-state")).toHaveText("in annotation");
  await submitAndSendBack(page, "Once more.", async () => {
    await page.locator("body").click({ position: { x: 5, y: 5 } });
    await page.keyboard.press("v"); // Select's key: its button is left out while locked
    await expect(page.getByTestId("photo-tool-select")).toHaveAttribute("aria-pressed", "true");
  });
  await expect(page.getByTestId("photo-tool-select")).toHaveAttribute("aria-pressed", "true");
});
