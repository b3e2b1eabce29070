// User story: an annotator opens a scene, sees masks, support arrows and the 3D scene, and
// corrects supports: in the object table, or on the photo (click an arrow, click or drag to
// the new supporter, keys to flip, remove, accept and reject), with each edge's provenance
// shown; the corrections are saved.
import { type APIRequestContext, type Browser, expect, test } from "@playwright/test";
import { getRevisions, getScene, seedScene, supportOf, T3D_1, T3D_5 } from "../helpers/api";
import { canvasColours } from "../helpers/canvas";
import { screenPoint } from "../helpers/objects";
import {
  arrowOf,
  arrowPoint,
  clickArrow,
  clickObject,
  dragArrowTo,
  objectPoint,
  openScene,
  setAuthor,
  slowAutosave,
} from "../helpers/photo";
import { screenshotPath } from "../helpers/screenshots";
import { importSynthetic, synthesize } from "../helpers/synthetic";

// These tests watch unsaved state and save by hand; no-lost-work.spec.ts covers autosave.
test.beforeEach(async ({ page }) => {
  await slowAutosave(page);
});

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
  // A guess's tooltip names the model that made it.
  await expect(page.getByTestId(`support-status-${child.id}`)).toHaveAttribute(
    "title",
    /^The pipeline's guess by the Relation Network v1, \d+% sure; nobody has checked it yet$/,
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
  await canvas.screenshot({ path: screenshotPath("scene3d.png") });
  await page.screenshot({ path: screenshotPath("scene-page.png"), fullPage: true });

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
  await page.screenshot({ path: screenshotPath("saved.png"), fullPage: true });

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

/**
 * Two annotators, each in their own browser, open the same revision; Alice puts the second
 * object on the first and saves, so Bob's page is one revision behind.
 */
async function bobBehindAlice(browser: Browser, request: APIRequestContext, name: string) {
  const seeded = await seedScene(request, T3D_5, name);
  const [first, second, , fourth] = seeded.scene.objects ?? [];
  if (!first || !second || !fourth) throw new Error("the seeded scene has too few objects");
  const alice = await (await browser.newContext()).newPage();
  const bob = await (await browser.newContext()).newPage();
  await slowAutosave(alice);
  await slowAutosave(bob);
  await openScene(alice, seeded.scene_id);
  await openScene(bob, seeded.scene_id);

  await alice.getByTestId(`supporter-select-${second.id}`).selectOption(first.id);
  await alice.getByTestId("save-button").click();
  await expect(alice.getByTestId("save-status")).toHaveAttribute("data-state", "saved");
  return { seeded, first, second, fourth, bob };
}

test("a save based on a stale revision that changed the same object shows a conflict and keeps the edit", async ({
  browser,
  request,
}) => {
  const behind = await bobBehindAlice(browser, request, "t3d-5 conflict");
  const { seeded, second, fourth, bob } = behind;

  // Bob saves on the revision he loaded, which is no longer the latest, a change of the same
  // object (the wall holds it up, from behind) and of another.
  await bob.getByTestId(`supporter-select-${second.id}`).selectOption("wall");
  await bob.getByTestId(`supporter-select-${fourth.id}`).selectOption("wall");
  await bob.getByTestId("save-button").click();
  const conflict = bob.getByTestId("conflict-message");
  await expect(conflict).toBeVisible();
  await expect(conflict).toContainText("not saved");
  await expect(bob.getByTestId("save-status")).toHaveAttribute("data-state", "conflict");
  // His edits are still there, visibly unsaved.
  await expect(bob.getByTestId(`type-select-${fourth.id}`)).toHaveValue("behind");
  await expect(bob.getByTestId(`arrow-${fourth.id}`)).toHaveAttribute("data-pending", "true");
  await expect(bob.getByTestId("pending-edits")).toContainText(fourth.id);
  await bob.screenshot({ path: screenshotPath("conflict.png"), fullPage: true });

  // Reload: Bob is told about the object both changed, his edits are re-applied on top.
  await bob.getByTestId("conflict-reload").click();
  await expect(conflict).toBeHidden();
  await expect(bob.getByTestId("reload-notice")).toContainText(`Both of you changed ${second.id}`);
  await expect(bob.getByTestId(`supporter-select-${second.id}`)).toHaveValue("wall");
  await expect(bob.getByTestId(`type-select-${fourth.id}`)).toHaveValue("behind");
  await expect(bob.getByTestId("save-status")).toHaveAttribute("data-state", "dirty");
  await bob.getByTestId("save-button").click();
  await expect(bob.getByTestId("save-status")).toHaveAttribute("data-state", "saved");

  const doc = await getScene(request, seeded.scene_id);
  expect(doc.revision).toBe(seeded.revision + 2);
  expect(supportOf(doc, second.id)).toMatchObject({ parent: "wall", source: "manual" });
  expect(supportOf(doc, fourth.id)).toMatchObject({ type: "behind", source: "manual" });
});

test("a save based on a stale revision that changed other objects goes on top by itself", async ({
  browser,
  request,
}) => {
  const behind = await bobBehindAlice(browser, request, "t3d-5 disjoint saves");
  const { seeded, first, second, fourth, bob } = behind;

  // Bob changes another object on the revision he loaded: no choice to make, so no conflict.
  await bob.getByTestId(`supporter-select-${fourth.id}`).selectOption("wall");
  await bob.getByTestId("save-button").click();
  await expect(bob.getByTestId("save-status")).toHaveAttribute("data-state", "saved");
  await expect(bob.getByTestId("conflict-message")).toBeHidden();
  const notice = bob.getByTestId("reload-notice");
  await expect(notice).toContainText("Your 1 change touches other objects: it is saved on top.");
  await expect(notice).toContainText(`Changed since revision ${seeded.revision}`);
  // Alice's change is on his page now.
  await expect(bob.getByTestId(`supporter-select-${second.id}`)).toHaveValue(first.id);

  const doc = await getScene(request, seeded.scene_id);
  expect(doc.revision).toBe(seeded.revision + 2);
  expect(supportOf(doc, second.id)).toMatchObject({ parent: first.id, source: "manual" });
  expect(supportOf(doc, fourth.id)).toMatchObject({ parent: "wall", type: "behind" });
});

test("edits supports on the photo with clicks, a drag and keys, showing each edge's provenance", async ({
  page,
  request,
}) => {
  const seeded = await seedScene(request, T3D_5, "t3d-5 photo editing");
  const guess = (id: string) => {
    const s = supportOf(seeded, id);
    if (!s) throw new Error(`the pipeline gave ${id} no supporter`);
    return s;
  };
  await openScene(page, seeded.scene_id);
  await setAuthor(page, "e2e-photo");
  const arrow = (id: string) => page.getByTestId(`arrow-${id}`);
  const flipped = (t: string) => (t === "below" ? "behind" : "below");

  // Click an arrow: it is selected, and its provenance is shown (a guess, with confidence).
  await clickArrow(page, "o1");
  await expect(arrow("o1")).toHaveClass(/is-selected/);
  await expect(page.getByTestId("edge-info-edge")).toHaveText(
    `o1 (night stand) on ${guess("o1").parent}, ${guess("o1").type}`,
  );
  await expect(page.getByTestId("edge-info-provenance")).toContainText("predicted (auto");
  await expect(arrow("o1")).toHaveAttribute("data-source", "auto");
  await page.screenshot({ path: screenshotPath("photo-arrow-selected.png") });

  // Click the new supporter: the arrow moves at once, unsaved and manual.
  await clickObject(page, "o0");
  await expect(arrow("o1")).toHaveAttribute("data-parent", "o0");
  await expect(arrow("o1")).toHaveAttribute("data-pending", "true");
  await expect(arrow("o1")).toHaveAttribute("data-source", "manual");
  await expect(page.getByTestId("edge-info-provenance")).toHaveText("your edit, not saved yet");

  // The pick is spent: clicking objects now only selects them, as someone looking around would.
  await expect(page.getByTestId("photo")).not.toHaveClass(/is-picking/);
  await clickObject(page, "o2");
  await clickObject(page, "o3");
  await expect(arrow("o1")).toHaveAttribute("data-parent", "o0");
  await expect(arrow("o2")).toHaveAttribute("data-parent", guess("o2").parent);
  await expect(arrow("o2")).toHaveAttribute("data-source", "auto");
  // S arms a pick for the object selected otherwise: the next click picks its supporter.
  await clickObject(page, "o1");
  await page.keyboard.press("s");
  await expect(page.getByTestId("photo")).toHaveClass(/is-picking/);
  await clickObject(page, "o0");
  await expect(arrow("o1")).toHaveAttribute("data-parent", "o0");
  await expect(arrow("o1")).toHaveClass(/is-selected/);
  // While a pick is armed, a click on another object's drawn arrow takes up that arrow: a
  // person looking from arrow to arrow changes nothing. Its mask (and its arrow's head, at its
  // centre) picks it.
  await clickArrow(page, "o2");
  await expect(page.getByTestId("photo")).toHaveClass(/is-picking/);
  const onBedsArrow = await arrowPoint(page, "o0");
  await page.mouse.click(onBedsArrow.x, onBedsArrow.y);
  await expect(arrow("o0")).toHaveClass(/is-selected/);
  await expect(page.getByTestId("photo-tool-options")).toContainText("holds up o0");
  await expect(arrow("o2")).toHaveAttribute("data-parent", guess("o2").parent);
  await clickArrow(page, "o2");
  await clickObject(page, "o0");
  await expect(arrow("o2")).toHaveAttribute("data-parent", "o0");
  await page.keyboard.press("Control+z");
  await expect(arrow("o2")).toHaveAttribute("data-parent", guess("o2").parent);
  // A supporter from below that stands beside its object on the photo is questioned.
  await clickObject(page, "o1");
  await page.keyboard.press("s");
  await clickObject(page, "o3");
  await expect(arrow("o1")).toHaveAttribute("data-parent", "o3");
  await expect(page.getByTestId("edge-info-doubt")).toHaveText(
    "o3 is beside o1 on the photo, not under it: is it the right supporter?",
  );
  // The object list flags it too (set there, the line under the photo may be out of view).
  await expect(page.getByTestId("support-status-o1")).toHaveClass(/badge--warn/);
  await expect(page.getByTestId("support-status-o1")).toHaveAttribute("title", /beside o1/);
  await page.keyboard.press("Control+z");
  await expect(page.getByTestId("edge-info-doubt")).toBeHidden();
  await expect(page.getByTestId("object-row-o1")).toHaveClass(/is-selected/);

  // T flips below/behind; Shift+Delete removes the supporter; Ctrl+Z brings it back.
  const typeBefore = (await arrowOf(page, "o1"))?.type ?? "";
  await page.keyboard.press("t");
  await expect(arrow("o1")).toHaveAttribute("data-type", flipped(typeBefore));
  await page.keyboard.press("Shift+Delete");
  await expect(arrow("o1")).toHaveCount(0);
  await expect(page.getByTestId("unsupported-o1")).toBeVisible();
  await page.keyboard.press("Control+z");
  await expect(arrow("o1")).toHaveAttribute("data-parent", "o0");
  await expect(arrow("o1")).toHaveAttribute("data-type", flipped(typeBefore));

  // A accepts a guess as it is: same edge, now a person's.
  await clickArrow(page, "o2");
  await page.keyboard.press("a");
  await expect(arrow("o2")).toHaveAttribute("data-parent", guess("o2").parent);
  await expect(arrow("o2")).toHaveAttribute("data-source", "manual");
  await expect(arrow("o2")).toHaveAttribute("data-pending", "true");

  // Drag an arrowhead onto another object: it becomes the supporter.
  await dragArrowTo(page, "o3", "o2");
  await expect(arrow("o3")).toHaveAttribute("data-parent", "o2");
  await expect(arrow("o3")).toHaveClass(/is-selected/);
  // Dropped where there is no object (the margin beyond the photo): nothing changes, and the
  // page says how to choose the floor, a wall or the ceiling.
  const head = await arrowPoint(page, "o3", "head");
  const nowhere = await screenPoint(page, -20, -20);
  await page.mouse.move(head.x, head.y);
  await page.mouse.down();
  await page.mouse.move(nowhere.x, nowhere.y, { steps: 6 });
  await page.mouse.up();
  await expect(page.getByTestId("edit-message")).toContainText("Dropped on no object");
  await expect(page.getByTestId("drop-hint")).toContainText("F floor, W wall, C ceiling");
  await expect(arrow("o3")).toHaveAttribute("data-parent", "o2");
  // Dragged over the floor between objects, the drop names it, and dropped there the floor
  // holds the object up (from below). The photo's bottom rows are searched for floor no mask
  // covers, as a person's eye would find it.
  const { width, height } = seeded.scene.image;
  const from = await arrowPoint(page, "o3", "head");
  await page.mouse.move(from.x, from.y);
  await page.mouse.down();
  let floorAt: { x: number; y: number } | null = null;
  for (let y = height - 6; y > height * 0.6 && !floorAt; y -= 25) {
    for (let x = 10; x < width && !floorAt; x += 30) {
      const at = await screenPoint(page, x, y);
      await page.mouse.move(at.x, at.y, { steps: 2 });
      const named = await page.getByTestId("drop-surface").allTextContents();
      if (named.includes("floor")) floorAt = at;
    }
  }
  expect(floorAt).not.toBeNull();
  await page.mouse.up();
  await expect(arrow("o3")).toHaveAttribute("data-parent", "floor");
  await expect(arrow("o3")).toHaveAttribute("data-type", "below");
  await page.keyboard.press("Control+z"); // back on o2, as the steps below expect
  await expect(arrow("o3")).toHaveAttribute("data-parent", "o2");
  // A click on the arrow arms a pick; pointing at the floor then names nothing (a click there
  // deselects, it picks no supporter). The arrow is clicked where it is drawn once the undo's
  // redraw has been painted (on a loaded machine the click otherwise met the old drawing).
  await page.mouse.move(4, 4);
  await page.evaluate(
    () => new Promise((done) => requestAnimationFrame(() => requestAnimationFrame(done))),
  );
  await clickArrow(page, "o3");
  await expect(page.getByTestId("photo")).toHaveClass(/is-picking/);
  await page.mouse.move(floorAt?.x ?? 0, floorAt?.y ?? 0, { steps: 2 });
  // Read at once, as drawn for this pointer position (a later redraw of the photo clears it).
  expect(await page.getByTestId("drop-surface").count()).toBe(0);
  await page.keyboard.press("Escape");
  await expect(arrow("o3")).toHaveAttribute("data-parent", "o2");

  // R rejects a guess: it goes, and the model's next answer (if it has one) is suggested.
  await expect(page.getByTestId("suggestion-status")).toContainText(/objects? scored in/, {
    timeout: 90_000,
  });
  const original = guess("o0");
  // Selected before the key (a click landing while the arrows are redrawn, after an autosave
  // or the live suggestions, would leave o3's arrow selected, and R would reject that).
  await expect(async () => {
    await clickArrow(page, "o0");
    await expect(arrow("o0")).toHaveClass(/is-selected/, { timeout: 2_000 });
  }).toPass({ timeout: 30_000 });
  await page.keyboard.press("r");
  await expect
    .poll(async () => {
      const now = await arrowOf(page, "o0");
      return now === null || now.suggested;
    })
    .toBe(true);
  const next = await arrowOf(page, "o0");
  if (next) {
    expect(`${next.parent} ${next.type}`).not.toBe(`${original.parent} ${original.type}`);
    await expect(arrow("o0")).toHaveAttribute("data-source", "model");
    await expect(page.getByTestId("edge-info-provenance")).toContainText("suggested by the model");
    await page.keyboard.press("a"); // take the suggestion
    await expect(arrow("o0")).toHaveAttribute("data-source", "manual");
  } else {
    await page.keyboard.press("f"); // no other answer: the floor holds it
    await expect(arrow("o0")).toHaveAttribute("data-parent", "floor");
  }
  const o0 = await arrowOf(page, "o0");

  // Hovering an object keeps only its edges in view; the rest fade.
  await page.keyboard.press("Escape");
  const hover = await objectPoint(page, "o2");
  await page.mouse.move(hover.x, hover.y);
  await expect(page.getByTestId("photo")).toHaveClass(/has-hover/);
  for (const id of ["o0", "o1", "o2", "o3"]) {
    const a = await arrowOf(page, id);
    const related = id === "o2" || a?.parent === "o2";
    const opacity = Number(await arrow(id).evaluate((n) => getComputedStyle(n).opacity));
    if (related) expect(opacity, `${id} is o2's edge`).toBe(1);
    else expect(opacity, `${id} is not o2's edge`).toBeLessThan(0.5);
  }
  await page.screenshot({ path: screenshotPath("photo-hover-fading.png") });

  // H hides the arrows and shows them again.
  await page.mouse.move(0, 0);
  await page.keyboard.press("h");
  await expect(page.getByTestId("arrow-layer")).toBeHidden();
  await expect(page.getByTestId("toggle-arrows")).not.toBeChecked();
  await page.keyboard.press("h");
  await expect(page.getByTestId("arrow-layer")).toBeVisible();

  // Save, reload: every edge records who set it and when, shown on the arrow and on select.
  await page.keyboard.press("Control+s");
  await expect(page.getByTestId("save-status")).toHaveAttribute("data-state", "saved");
  await page.reload();
  await expect(page.getByTestId("photo")).toHaveAttribute("data-loaded", "true");
  for (const id of ["o0", "o1", "o2", "o3"]) {
    await expect(arrow(id)).toHaveAttribute("data-source", "manual");
    await expect(arrow(id)).toHaveAttribute("data-author", "e2e-photo");
    await expect(arrow(id)).toHaveAttribute("data-time", /^\d{4}-\d\d-\d\dT/);
  }
  await clickArrow(page, "o1");
  await expect(page.getByTestId("edge-info-provenance")).toContainText("manual · e2e-photo");
  await page.screenshot({ path: screenshotPath("photo-provenance.png") });

  const doc = await getScene(request, seeded.scene_id);
  expect(supportOf(doc, "o1")).toMatchObject({
    parent: "o0",
    type: flipped(typeBefore),
    source: "manual",
    author: "e2e-photo",
  });
  expect(supportOf(doc, "o2")).toMatchObject({ parent: guess("o2").parent, source: "manual" });
  expect(supportOf(doc, "o3")).toMatchObject({ parent: "o2", source: "manual" });
  expect(supportOf(doc, "o0")).toMatchObject({ parent: o0?.parent, type: o0?.type });
  for (const s of doc.scene.supports ?? []) expect(s.time).toBeTruthy();
});

test("a supporter's arrows start apart, under each child, clear of its centre, and picking the supporter it has edits nothing", async ({
  page,
  request,
}) => {
  const [synthetic] = synthesize(15, 1); // a crowded room: shelves that hold up many things
  if (!synthetic) throw new Error("no synthetic scene");
  const seeded = await importSynthetic(request, synthetic, "synthetic crowded clicks");
  const supports = seeded.scene.supports ?? [];
  const held = (id: string) => supports.filter((s) => s.parent === id).length;
  const ids = (seeded.scene.objects ?? []).map((o) => o.id);
  const supporter = ids.sort((a, b) => held(b) - held(a))[0];
  if (!supporter || held(supporter) < 2) throw new Error("no object holds up two others");
  await openScene(page, seeded.scene_id);

  // Its children's arrows begin on it under each child, not all at its centre (they fanned out
  // of it, too close to tell apart or click).
  const tails = await page.evaluate(
    (id) =>
      [...document.querySelectorAll<SVGGElement>(`.arrow[data-parent="${id}"][data-type="below"]`)]
        .map((arrow) => arrow.querySelector<SVGCircleElement>(".arrow-tail"))
        .map((tail) => `${tail?.cx.baseVal.value.toFixed(0)},${tail?.cy.baseVal.value.toFixed(0)}`),
    supporter,
  );
  expect(tails.length).toBeGreaterThanOrEqual(2);
  expect(new Set(tails).size).toBe(tails.length);
  // Where an arrow begins takes no click on it: people click there to select the supporter
  // (an object in front may take it, its mask being on top; so may another arrow passing).
  const atTails = await page.evaluate((id) => {
    const arrows = [...document.querySelectorAll<SVGGElement>(`.arrow[data-parent="${id}"]`)];
    return arrows.flatMap((arrow) => {
      const tail = arrow.querySelector<SVGCircleElement>(".arrow-tail");
      const matrix = tail?.getScreenCTM();
      if (!tail || !matrix) return [];
      const from = new DOMPoint(tail.cx.baseVal.value, tail.cy.baseVal.value);
      const at = from.matrixTransform(matrix);
      const hit = document.elementFromPoint(at.x, at.y)?.closest<SVGGElement>(".arrow");
      return [hit === arrow ? `its own arrow, ${arrow.dataset.child}` : "not its own arrow"];
    });
  }, supporter);
  expect(atTails.length).toBeGreaterThanOrEqual(2);
  expect(new Set(atTails)).toEqual(new Set(["not its own arrow"]));

  // A child's arrow selected, a click on the supporter it has already changes nothing.
  const child = supports.find((s) => s.parent === supporter)?.child ?? "";
  await clickArrow(page, child);
  await expect(page.getByTestId(`arrow-${child}`)).toHaveClass(/is-selected/);
  await clickObject(page, supporter);
  await expect(page.getByTestId("edit-message")).toContainText(
    `${child} is on ${supporter} already`,
  );
  await expect(page.getByTestId(`arrow-${child}`)).toHaveAttribute("data-pending", "false");
  await expect(page.getByTestId("save-status")).toContainText("no unsaved changes");
});

test("a crowded photo at 1280x800: a click near an object's centre only selects it, an armed pick is said above the photo, and the selected row shows in the window", async ({
  page,
  request,
}) => {
  const seeded = await seedScene(request, T3D_1, "t3d-1 picking");
  await openScene(page, seeded.scene_id);
  await page.getByTestId("photo").evaluate((photo) => photo.scrollIntoView({ block: "center" }));
  // A point of an arrow's wide hit margin, off the arrow drawn, inside its own object's mask
  // (the arrow runs over its object to the centre, where people click to select it).
  const candidates = await page.evaluate(() =>
    [...document.querySelectorAll<SVGGElement>(".arrow[data-child]")].flatMap((arrow) => {
      const shaft = arrow.querySelector<SVGPathElement>(".arrow-shaft");
      const matrix = shaft?.getScreenCTM();
      if (!shaft || !matrix) return [];
      const length = shaft.getTotalLength();
      return [0.6, 0.7, 0.8].flatMap((f) => {
        const q = shaft.getPointAtLength(length * f);
        const s = new DOMPoint(q.x, q.y).matrixTransform(matrix);
        return [7, -7].flatMap((dx) => {
          const hit = document.elementFromPoint(s.x + dx, s.y);
          return hit?.classList.contains("arrow-hit") && hit.closest(".arrow") === arrow
            ? [{ child: arrow.dataset.child ?? "", x: s.x + dx, y: s.y }]
            : [];
        });
      });
    }),
  );
  // The middle of a drawn arrow's head, at its object's centre (where people click to select
  // the object).
  const heads = await page.evaluate(() =>
    [...document.querySelectorAll<SVGGElement>(".arrow[data-child]")].flatMap((arrow) => {
      const head = arrow.querySelector<SVGPathElement>(".arrow-head");
      const matrix = head?.getScreenCTM();
      if (!head || !matrix) return [];
      const box = head.getBBox();
      const middle = new DOMPoint(box.x + box.width / 2, box.y + box.height / 2);
      const s = middle.matrixTransform(matrix);
      const hit = document.elementFromPoint(s.x, s.y);
      return hit && !hit.classList.contains("arrow-hit") && hit.closest(".arrow") === arrow
        ? [{ child: arrow.dataset.child ?? "", x: s.x, y: s.y }]
        : [];
    }),
  );
  // Which of them lie in their own object's mask: hovered with the arrows hidden.
  const inOwnObject = async (points: { child: string; x: number; y: number }[]) => {
    await page.getByTestId("toggle-arrows").uncheck();
    let found: { child: string; x: number; y: number } | null = null;
    for (const point of points) {
      await page.mouse.move(point.x, point.y);
      if (await page.getByTestId(`mask-${point.child}`).evaluate((n) => n.matches(".is-hovered"))) {
        found = point;
        break;
      }
    }
    await page.getByTestId("toggle-arrows").check();
    return found;
  };
  const margin = await inOwnObject(candidates);
  if (!margin)
    throw new Error(`none of ${candidates.length} points of arrow margins is in its own object`);
  await page.mouse.click(margin.x, margin.y);
  await expect(page.getByTestId(`object-row-${margin.child}`)).toHaveClass(/is-selected/);
  await expect(page.getByTestId("photo")).not.toHaveClass(/is-picking/);
  // Another object's (the one selected would stay selected whatever the click did).
  const head = await inOwnObject(heads.filter((h) => h.child !== margin.child));
  if (!head) throw new Error(`none of ${heads.length} arrow heads is in its own object`);
  await page.mouse.click(head.x, head.y);
  await expect(page.getByTestId(`object-row-${head.child}`)).toHaveClass(/is-selected/);
  await expect(page.getByTestId("photo")).not.toHaveClass(/is-picking/);
  // The drawn arrow arms the pick; the tool row (in view while working on the photo) says so,
  // and the object under the pointer shows the arrow a click would give.
  await clickArrow(page, margin.child);
  await expect(page.getByTestId("photo")).toHaveClass(/is-picking/);
  await expect(page.getByTestId("photo-tool-options")).toContainText(
    `Now click the object that holds up ${margin.child}`,
  );
  const other = (seeded.scene.objects ?? []).find((o) => o.id !== margin?.child)?.id ?? "";
  await objectPoint(page, other);
  await expect(page.getByTestId("drag-line")).toHaveCount(1);
  await page.keyboard.press("Escape");
  await expect(page.getByTestId("photo")).not.toHaveClass(/is-picking/);
  await expect(page.getByTestId("drag-line")).toHaveCount(0);
  await expect(page.getByTestId("photo-tool-options")).toContainText("Click an object or an arrow");
  // Armed again, a click at another object's centre (its arrow's head) picks that object.
  await clickArrow(page, margin.child);
  await expect(page.getByTestId("photo")).toHaveClass(/is-picking/);
  await page.mouse.click(head.x, head.y);
  await expect(page.getByTestId(`arrow-${margin.child}`)).toHaveAttribute(
    "data-parent",
    head.child,
  );
  await expect(page.getByTestId("photo")).not.toHaveClass(/is-picking/);

  // On a laptop's screen, before the page is scrolled, the editor's foot is below the window:
  // each object N selects has its row brought into the window, not only into the panel.
  await page.setViewportSize({ width: 1280, height: 800 });
  await page.evaluate(() => window.scrollTo(0, 0));
  const count = seeded.scene.objects?.length ?? 0;
  expect(count).toBeGreaterThan(12);
  for (let i = 0; i < count; i++) {
    await page.locator("body").click({ position: { x: 5, y: 5 } });
    await page.keyboard.press("n");
    const selected = page.locator(".object-row.is-selected");
    await expect(selected).toHaveCount(1);
    await expect(selected).toBeInViewport({ ratio: 0.9 });
  }
});

test("T on an object the floor holds up does nothing, and says why where the tools are", async ({
  page,
  request,
}) => {
  const seeded = await seedScene(request, T3D_5, "t3d-5 floor type");
  const onFloor = (seeded.scene.supports ?? []).find((s) => s.parent === "floor");
  if (!onFloor) throw new Error("nothing stands on the floor in t3d-5");
  await openScene(page, seeded.scene_id);
  await page.getByTestId(`object-row-${onFloor.child}`).click();
  await page.locator("body").click({ position: { x: 5, y: 80 } }); // keys go to the page
  await page.getByTestId(`object-row-${onFloor.child}`).locator("th").click();
  await page.keyboard.press("t");
  await expect(page.getByTestId("photo-tool-options")).toContainText(
    `The floor holds ${onFloor.child} up from below only.`,
  );
  await expect(page.getByTestId(`arrow-${onFloor.child}`)).toHaveAttribute("data-type", "below");
  await expect(page.getByTestId("save-status")).toContainText("no unsaved changes");
  await expect(page.getByTestId(`type-select-${onFloor.child}`)).toBeDisabled();
});
