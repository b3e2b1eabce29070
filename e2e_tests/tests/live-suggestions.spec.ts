// User story: the annotator corrects one edge and the remaining predictions follow at once.
// The Relation Network scored the photo and masks in the browser when the scene opened;
// after a correction the tree is decoded again with the correction pinned, and an object
// whose best answer changed shows it as a suggestion (dotted arrow), with no request to the
// server (every request is recorded from the correction until the arrow changed).
import type { Request } from "@playwright/test";
import { expect, test } from "@playwright/test";
import { getScene, postEdits, supportOf } from "../helpers/api";
import { nextDialog } from "../helpers/dialogs";
import {
  arrowOf,
  clickArrow,
  objectPoint,
  openScene,
  setAuthor,
  slowAutosave,
  waitForModel,
} from "../helpers/photo";
import { screenshotPath } from "../helpers/screenshots";
import { importSynthetic, synthesize } from "../helpers/synthetic";

const STRUCTURAL = new Set(["floor", "wall", "ceiling"]);

test("a correction re-scores the other predictions in the browser, without the server", async ({
  page,
  request,
}) => {
  const [synthetic] = synthesize(11, 1); // books and a box on a counter and tables
  if (!synthetic) throw new Error("no synthetic scene");
  const seeded = await importSynthetic(request, synthetic, "synthetic live suggestions");
  // An object the pipeline put on another object: a is on b.
  const stacked = (seeded.scene.supports ?? []).find(
    (s) => s.source === "auto" && !STRUCTURAL.has(s.parent),
  );
  if (!stacked) throw new Error("the synthetic scene has no object on another object");
  const a = stacked.child;
  const b = stacked.parent;

  await slowAutosave(page); // so that any request seen below is the suggestions' doing
  await openScene(page, seeded.scene_id);
  await setAuthor(page, "e2e-live");
  await waitForModel(page);
  await expect(page.getByTestId("suggestion-status")).toContainText("live: no guess to change");
  expect(await arrowOf(page, a)).toMatchObject({ parent: b, suggested: false, source: "auto" });

  const requests: string[] = [];
  const record = (r: Request) => requests.push(`${r.method()} ${r.url()}`);

  // The annotator says b stands on a: a's guess (on b) would now close a loop, so the model
  // answers again for a.
  await clickArrow(page, b);
  const point = await objectPoint(page, a);
  page.on("request", record);
  const started = Date.now();
  await page.mouse.click(point.x, point.y);
  await expect(page.getByTestId(`arrow-${b}`)).toHaveAttribute("data-parent", a);
  await expect(page.getByTestId(`arrow-${a}`)).toHaveAttribute("data-suggested", "true");
  const elapsed = Date.now() - started;
  page.off("request", record);
  expect(requests, "requests while the suggestions updated").toEqual([]);
  const suggestion = await arrowOf(page, a);
  expect(suggestion?.parent).not.toBe(b);
  expect(suggestion?.source).toBe("model");
  await expect(page.getByTestId("suggestion-status")).toContainText("live: 1 guess to change");
  // The list shows what A would accept: the suggestion, marked as not stored.
  const menu = page.getByTestId(`supporter-select-${a}`);
  await expect(menu).toHaveValue(suggestion?.parent ?? "");
  await expect(menu).toHaveClass(/is-suggested/);
  await expect(menu).toHaveAttribute("title", /the model's suggestion .* A accepts it/);
  console.log(
    `live suggestion: ${a} now on ${suggestion?.parent} (was ${b}), seen ${elapsed} ms after ` +
      "the click (Playwright's round trips included)",
  );
  await page.screenshot({ path: screenshotPath("live-suggestion.png") });

  // Undo takes the correction back, and the suggestion with it; redo brings both.
  await page.keyboard.press("Control+z");
  await expect(page.getByTestId(`arrow-${a}`)).toHaveAttribute("data-suggested", "false");
  await expect(page.getByTestId(`arrow-${a}`)).toHaveAttribute("data-parent", b);
  await expect(menu).toHaveValue(b);
  await expect(menu).not.toHaveClass(/is-suggested/);
  await page.keyboard.press("Control+Shift+z");
  await expect(page.getByTestId(`arrow-${a}`)).toHaveAttribute("data-suggested", "true");

  // Rejecting another guess: its next answer appears, again without a request.
  const other = (seeded.scene.supports ?? []).find((s) => s.child !== a && s.child !== b);
  if (!other) throw new Error("the scene has too few objects");
  await clickArrow(page, other.child);
  page.on("request", record);
  await page.keyboard.press("r");
  await expect
    .poll(async () => {
      const now = await arrowOf(page, other.child);
      return now === null || now.suggested;
    })
    .toBe(true);
  page.off("request", record);
  expect(requests, "requests while rejecting").toEqual([]);
  const replaced = await arrowOf(page, other.child);
  if (replaced)
    expect(`${replaced.parent} ${replaced.type}`).not.toBe(`${other.parent} ${other.type}`);

  // Accepting the suggestion for a makes it a person's edge; then save.
  await clickArrow(page, a);
  await page.keyboard.press("a");
  await expect(page.getByTestId(`arrow-${a}`)).toHaveAttribute("data-source", "manual");
  await page.keyboard.press("Control+s");
  await expect(page.getByTestId("save-status")).toHaveAttribute("data-state", "saved");
  const doc = await getScene(request, seeded.scene_id);
  expect(supportOf(doc, b)).toMatchObject({ parent: a, source: "manual", author: "e2e-live" });
  expect(supportOf(doc, a)).toMatchObject({ parent: suggestion?.parent, source: "manual" });
});

test("a person's label the model is sure is something else is flagged, not changed", async ({
  page,
  request,
}) => {
  const [synthetic] = synthesize(11, 1);
  if (!synthetic) throw new Error("no synthetic scene");
  const seeded = await importSynthetic(request, synthetic, "synthetic doubted label");
  await openScene(page, seeded.scene_id);
  await waitForModel(page);
  await expect(page.locator(".badge--doubt")).toHaveCount(0);
  // An object the model places confidently (80% or more), on something other than the ceiling.
  const sure = await page.getByTestId(/^support-suggestion-/).evaluateAll((badges) =>
    badges
      .map((b) => ({
        id: (b.getAttribute("data-testid") ?? "").replace("support-suggestion-", ""),
        text: b.textContent ?? "",
      }))
      .filter((b) => Number(/(\d+)%$/.exec(b.text)?.[1] ?? 0) >= 80 && !b.text.includes("ceiling")),
  );
  const target = sure[0];
  if (!target) throw new Error("the model is sure of no object in this scene");

  // A person hangs it from the ceiling (a slip), and the page is opened again.
  const doc = await getScene(request, seeded.scene_id);
  await postEdits(request, doc, "e2e-doubt", [
    { kind: "set_support", child: target.id, parent: "ceiling", type: "behind" },
  ]);
  await page.reload();
  await expect(page.getByTestId("photo")).toHaveAttribute("data-loaded", "true");
  await waitForModel(page);
  const badge = page.getByTestId(`support-suggestion-${target.id}`);
  await expect(badge).toHaveClass(/badge--doubt/);
  await expect(badge).toHaveAttribute("title", /sure of .* not the label set by a person/);
  await expect(page.getByTestId("suggestion-status")).toContainText(
    "the model disagrees with 1 label set by a person",
  );
  const stored = await getScene(request, seeded.scene_id);
  expect(supportOf(stored, target.id)?.parent).toBe("ceiling");
  await page.getByTestId("object-table").screenshot({ path: screenshotPath("doubted-label.png") });

  // Submitting asks about it first: a reviewer would send a slip back.
  const submit = page.getByTestId("workflow-submit");
  await expect(submit).toBeEnabled();
  const question = nextDialog(page, "dismiss");
  await submit.click();
  expect(await question).toContain(
    `1 object (${target.id}) has a supporter set by a person that the support model is sure ` +
      "is something else (orange in the list)",
  );
  await expect(page.getByTestId("workflow-state")).toHaveText("in annotation");
});
