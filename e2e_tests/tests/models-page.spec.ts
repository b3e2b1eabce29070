// User story: an admin sees how many labelled scenes there are, retrains the Relation Network
// from the page, watches the job, sees the new model's curve, makes it active (the page asks
// first, with both models' figures) and rolls
// back to the model that was active before. The page's list, curve and history follow.
import type { ModelInfo } from "@holiscene/schema";
import { type APIRequestContext, expect, test } from "@playwright/test";
import { postEdits, seedScene, T3D_1, T3D_5 } from "../helpers/api";
import { screenshotPath } from "../helpers/screenshots";

async function models(request: APIRequestContext): Promise<ModelInfo[]> {
  const response = await request.get("/api/models?kind=relation");
  expect(response.status()).toBe(200);
  return (await response.json()) as ModelInfo[];
}

/** A scene whose first object's supporter a person set: labelled for retraining. Two photos:
 * scenes of one photo are all trained on or all held out. */
async function labelledScene(request: APIRequestContext, name: string, dir: string): Promise<void> {
  const doc = await seedScene(request, dir, name);
  const child = doc.scene.objects?.[0]?.id ?? "o0";
  await postEdits(request, doc, "e2e-admin", [
    { kind: "set_support", child, parent: "floor", type: "below" },
  ]);
}

test("an admin retrains, makes the new model active and rolls back", async ({ page }) => {
  test.setTimeout(300_000);
  await labelledScene(page.request, "labelled for retraining 1", T3D_5);
  await labelledScene(page.request, "labelled for retraining 2", T3D_1);
  const before = await models(page.request);
  const active = before.find((m) => m.active);
  if (!active) throw new Error("no active Relation Network");

  await page.goto("/#/dashboard");
  await page.getByTestId("models-link").click(); // in the header, on every page
  await expect(page.getByTestId("model-list")).toBeVisible();
  await expect(page.getByTestId("models-admin-only")).toBeHidden(); // single-user mode: admin
  // Before Retrain, the form says how many labelled scenes it would learn from.
  await expect(page.getByTestId("retrain-readiness")).toContainText(
    /\d+ labelled scenes \(scenes with supports set by a person, rejected ones left out\): \d+ of them (is|are) held out/,
  );
  await page.getByTestId("retrain-epochs").fill("1");
  await page.getByTestId("retrain-synthetic").fill("20");
  await page.getByTestId("retrain-button").click();
  await expect(page.getByTestId("retrain-progress")).toBeVisible();
  await expect(page.getByTestId("retrain-progress")).toHaveAttribute("data-status", "succeeded", {
    timeout: 240_000,
  });
  const after = await models(page.request);
  const trained = after.find((m) => !before.some((b) => b.id === m.id));
  if (!trained) throw new Error("the retrain registered no model");
  const row = page.getByTestId(`model-row-${trained.version}`);
  await expect(row).toBeVisible();
  // Its held-out figure says how many labelled objects it rests on.
  await expect(row).toContainText(`on ${trained.heldout_items} labelled object`);
  // The card shows the curve the admin waited for, not the active model's.
  const curveTitle = page.locator(".card h2", { hasText: "Training curve of" });
  await expect(curveTitle).toHaveText(
    `Training curve of v${trained.version} (${trained.active ? "active" : trained.status})`,
  );
  await page.screenshot({ path: screenshotPath("models-retrained.png"), fullPage: true });

  // A model more accurate on the held-out scenes became active by itself; one exactly as
  // accurate (a candidate) or worse is made active by hand. The page asks first, every time.
  const asked: string[] = [];
  page.on("dialog", (dialog) => {
    asked.push(dialog.message());
    void dialog.accept();
  });
  if (trained.active) {
    expect(trained.status).toBe("accepted");
  } else {
    expect(["candidate", "rejected"]).toContain(trained.status);
    await page.getByTestId(`promote-${trained.version}`).click();
    await expect(row).toHaveClass(/is-active/);
    if (trained.status === "rejected") {
      await expect(row).toContainText("rejected, made active by hand");
      expect(asked.at(-1)).toContain("did worse than the model it was compared with");
    }
    // The question puts both models' figures side by side.
    expect(asked.at(-1)).toContain(`Make v${trained.version} the active model?`);
    expect(asked.at(-1)).toContain(`v${active.version} (active now): held-out accuracy`);
  }
  await expect(row).toHaveClass(/is-active/);
  await expect(page.getByTestId("model-history")).toContainText(`v${trained.version}`);
  await expect(curveTitle).toHaveText(`Training curve of v${trained.version} (active)`);

  // Roll back: the model active before is active again, on the page and on the server.
  await page.getByTestId(`promote-${active.version}`).click();
  await expect(page.getByTestId(`model-row-${active.version}`)).toHaveClass(/is-active/);
  expect(asked.at(-1)).toContain(`Make v${active.version} the active model?`);
  // The card follows to the model made active (it may have no curve: the card says so).
  await expect(curveTitle).toHaveText(`Training curve of v${active.version} (active)`);
  // The job's outcome line stays, marked as history: it no longer says which model is active.
  await expect(page.getByTestId("retrain-since")).toBeVisible();
  await expect(row).not.toHaveClass(/is-active/);
  expect((await models(page.request)).find((m) => m.active)?.id).toBe(active.id);
});

test("the detector list says which network each version is", async ({ page }) => {
  const response = await page.request.get("/api/models?kind=detector");
  expect(response.status()).toBe(200);
  const detectors = (await response.json()) as ModelInfo[];
  const named = detectors.filter((m) => m.name);
  expect(named.length).toBeGreaterThanOrEqual(2);
  await page.goto("/#/models");
  await page.getByTestId("model-kind-detector").click();
  for (const model of named) {
    await expect(page.getByTestId(`model-row-${model.version}`).locator(".model-name")).toHaveText(
      model.name ?? "",
    );
  }
  const active = detectors.find((m) => m.active);
  expect(active?.name).toContain("PicoDet");
  // A converted detector has no validation figure: its "—" says why.
  const converted = detectors.find((m) => m.validation_accuracy === null);
  if (!converted) throw new Error("no converted detector in the registry");
  const validation = page.getByTestId(`model-row-${converted.version}`).locator("td").nth(3);
  await expect(validation).toHaveText("—");
  await expect(validation).toHaveAttribute("title", /^Not trained here/);
});

test("an admin cancels a long retrain: it stops, says who cancelled it, and registers nothing", async ({
  page,
}) => {
  test.setTimeout(120_000);
  await labelledScene(page.request, "labelled before a cancel 1", T3D_5);
  await labelledScene(page.request, "labelled before a cancel 2", T3D_1);
  const before = await models(page.request);
  await page.goto("/#/models");
  await page.getByTestId("retrain-epochs").fill("500");
  await page.getByTestId("retrain-synthetic").fill("5000");
  await page.getByTestId("retrain-button").click();
  const cancel = page.getByTestId("retrain-cancel");
  await expect(cancel).toBeVisible();
  // While it runs, the curve card says the new curve comes when it ends, and the line says how
  // long it has run.
  await expect(page.getByTestId("curve-waiting")).toBeVisible();
  await expect(page.getByTestId("retrain-progress")).toContainText(/\d+ s so far/, {
    timeout: 20_000,
  });
  page.once("dialog", (dialog) => void dialog.accept()); // asked first
  await cancel.click();
  const progress = page.getByTestId("retrain-progress");
  await expect(progress).toHaveAttribute("data-status", "cancelled", { timeout: 60_000 });
  await expect(progress).toContainText("Retraining cancelled by");
  await expect(progress).not.toHaveClass(/is-failed/);
  await expect(progress.locator("progress")).toBeHidden(); // no bar part filled beside it
  await expect(page.getByTestId("curve-waiting")).toBeHidden();
  await expect(cancel).toBeHidden();
  await expect(page.getByTestId("retrain-button")).toBeEnabled();
  expect((await models(page.request)).map((m) => m.id)).toEqual(before.map((m) => m.id));

  // Another retrain started elsewhere: the page's refusal replaces the cancelled job's line,
  // which would read as this attempt's outcome.
  const elsewhere = await page.request.post("/api/models/retrain?kind=relation", {
    data: { max_epochs: 500, synthetic_scenes: 5000 },
  });
  expect(elsewhere.status()).toBe(202);
  await page.getByTestId("retrain-button").click();
  await expect(page.getByTestId("retrain-error")).toContainText("Retraining did not start");
  await expect(progress).toBeHidden();
  // The detector's tab says which retrain its own waits for, until that one ends.
  await page.getByTestId("model-kind-detector").click();
  const readiness = page.getByTestId("retrain-readiness");
  await expect(readiness).toContainText("Waiting: a retrain of the Relation Network started by");
  await expect(page.getByTestId("retrain-button")).toBeDisabled();
  await page.screenshot({ path: screenshotPath("models-waiting-for-other.png"), fullPage: true });
  const { id } = (await elsewhere.json()) as { id: string };
  expect((await page.request.post(`/api/models/retrain/${id}/cancel`)).status()).toBe(200);
  await expect(readiness).not.toContainText("Waiting", { timeout: 20_000 });
});
