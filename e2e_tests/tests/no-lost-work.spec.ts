// User story: no lost work. Undo and redo across every edit (a taken-back acceptance gives
// the pipeline's guess back as a guess); edits save themselves after a short idle time and
// survive a reload; edits whose save failed survive a closed tab (localStorage) and are
// offered back; the history shows each revision's diff and can revert; when two people change
// the same object the second gets a clear conflict message and can merge or reload, keeping
// their edit.
import type { SceneDocument, SupportRelation } from "@holiscene/schema";
import { expect, type Page, test } from "@playwright/test";
import { getRevisions, getScene, postEdits, seedScene, supportOf, T3D_5 } from "../helpers/api";
import { draftKeys, keptDraft } from "../helpers/drafts";
import { arrowOf, clickArrow, clickObject, openScene, setAuthor } from "../helpers/photo";
import { screenshotPath } from "../helpers/screenshots";

const flip = (t: string) => (t === "below" ? "behind" : "below");

function guessOf(doc: SceneDocument, id: string): SupportRelation {
  const s = supportOf(doc, id);
  if (!s) throw new Error(`no supporter for ${id}`);
  return s;
}

/** Wait until autosave has saved everything (no click: the idle timer does it). */
async function autosaved(page: Page): Promise<void> {
  await expect(page.getByTestId("save-status")).toHaveAttribute("data-state", "saved", {
    timeout: 20_000,
  });
}

test("undo and redo across edits, autosave after idle, and a reload keeps the edits", async ({
  page,
  request,
}) => {
  const seeded = await seedScene(request, T3D_5, "t3d-5 undo");
  const o1 = guessOf(seeded, "o1");
  const o2 = guessOf(seeded, "o2");
  const posts: string[] = [];
  page.on("request", (r) => {
    if (r.method() === "POST" && r.url().endsWith("/edits")) posts.push(r.url());
  });
  await openScene(page, seeded.scene_id);
  await setAuthor(page, "e2e-undo");

  await clickArrow(page, "o1");
  await clickObject(page, "o0"); // 1: o1 on o0
  await page.keyboard.press("t"); // 2: flip its type
  await clickArrow(page, "o2");
  await page.keyboard.press("a"); // 3: accept o2's guess
  await expect(page.getByTestId("arrow-o2")).toHaveAttribute("data-source", "manual");

  // Undo all three, in order; the accepted guess is a guess again.
  await page.keyboard.press("Control+z");
  await expect(page.getByTestId("arrow-o2")).toHaveAttribute("data-source", "auto");
  await page.keyboard.press("Control+z");
  await expect(page.getByTestId("arrow-o1")).toHaveAttribute("data-type", o1.type);
  await page.keyboard.press("Control+z");
  expect(await arrowOf(page, "o1")).toMatchObject({ parent: o1.parent, source: "auto" });
  await expect(page.getByTestId("undo-button")).toBeDisabled();

  // Redo two of them.
  await page.keyboard.press("Control+Shift+z");
  await expect(page.getByTestId("arrow-o1")).toHaveAttribute("data-parent", "o0");
  await page.keyboard.press("Control+Shift+z");
  await expect(page.getByTestId("arrow-o1")).toHaveAttribute("data-type", flip(o1.type));

  // Nobody clicks Save: after a short idle time the edits are on the server.
  await autosaved(page);
  expect(posts.length).toBeGreaterThan(0);
  let doc = await getScene(request, seeded.scene_id);
  expect(supportOf(doc, "o1")).toMatchObject({
    parent: "o0",
    type: flip(o1.type),
    source: "manual",
    author: "e2e-undo",
  });
  // o2's acceptance was undone: the guess as the pipeline stored it, whatever was saved between.
  expect(supportOf(doc, "o2")).toEqual(o2);

  // Undo works across saves too: taking back the flip saves again.
  await page.keyboard.press("Control+z");
  await expect(page.getByTestId("arrow-o1")).toHaveAttribute("data-type", o1.type);
  await autosaved(page);
  doc = await getScene(request, seeded.scene_id);
  expect(supportOf(doc, "o1")).toMatchObject({ parent: "o0", type: o1.type, source: "manual" });

  // Reloaded, the page shows what was saved.
  await page.reload();
  await expect(page.getByTestId("photo")).toHaveAttribute("data-loaded", "true");
  expect(await arrowOf(page, "o1")).toMatchObject({
    parent: "o0",
    type: o1.type,
    source: "manual",
  });
  expect(await arrowOf(page, "o2")).toMatchObject({ parent: o2.parent, source: "auto" });
  await expect(page.getByTestId("recovery-banner")).toBeHidden();
});

test("edits whose save failed survive a closed tab and are offered back", async ({
  context,
  request,
}) => {
  const seeded = await seedScene(request, T3D_5, "t3d-5 recovery");
  const page = await context.newPage();
  // The server never gets the edit: every save fails.
  await page.route("**/api/scenes/*/edits", (route) => route.abort("failed"));
  await openScene(page, seeded.scene_id);
  await setAuthor(page, "e2e-crash");
  await clickArrow(page, "o3");
  await page.keyboard.press("w"); // a wall holds o3
  await expect(page.getByTestId("arrow-o3")).toHaveAttribute("data-parent", "wall");
  await expect(page.getByTestId("save-status")).toHaveAttribute("data-state", "error", {
    timeout: 20_000,
  });
  const draft = await keptDraft(page, seeded.scene_id);
  expect(draft).toContain('"child":"o3"');
  // Closing the tab with the edit unsaved: the browser asks first; staying keeps the page.
  const asked = page.waitForEvent("dialog");
  await page.close({ runBeforeUnload: true });
  const leave = await asked;
  expect(leave.type()).toBe("beforeunload");
  await leave.dismiss();
  await expect(page.getByTestId("arrow-o3")).toHaveAttribute("data-parent", "wall");
  await page.close(); // the tab is gone, the edit never reached the server
  expect(supportOf(await getScene(request, seeded.scene_id), "o3")?.parent).not.toBe("wall");

  // Next visit: the edit is offered back; restoring it (Shift+U) saves it.
  const again = await context.newPage();
  await openScene(again, seeded.scene_id);
  const banner = again.getByTestId("recovery-banner");
  await expect(banner).toBeVisible();
  await expect(banner).toContainText("o3: on wall (behind)");
  await again.screenshot({ path: screenshotPath("recovery-offered.png") });
  // Submitting now would strand the offered edit: it waits until it is restored or discarded.
  await again.getByTestId("workflow-take").click();
  const submit = again.getByTestId("workflow-submit");
  await expect(submit).toBeVisible();
  await expect(submit).toBeDisabled();
  await expect(submit).toHaveAttribute("title", /Restore or discard the unsaved changes/);
  await expect(again.getByTestId("workflow-note")).toContainText("Restore or discard");
  await again.keyboard.press("Shift+U");
  await expect(banner).toBeHidden();
  await expect(again.getByTestId("arrow-o3")).toHaveAttribute("data-parent", "wall");
  await autosaved(again);
  await expect(submit).toBeEnabled();
  expect(supportOf(await getScene(request, seeded.scene_id), "o3")).toMatchObject({
    parent: "wall",
    type: "behind",
    source: "manual",
    author: "e2e-crash",
  });
  expect(await draftKeys(again, seeded.scene_id)).toEqual([]);
});

test("the history shows what each revision changed and reverts to any of them", async ({
  page,
  request,
}) => {
  const seeded = await seedScene(request, T3D_5, "t3d-5 history");
  const predicted = seeded.revision;
  const first = await postEdits(request, seeded, "alice", [
    { kind: "set_support", child: "o1", parent: "o0", type: "below" },
    {
      kind: "set_support",
      child: "o2",
      parent: guessOf(seeded, "o2").parent,
      type: guessOf(seeded, "o2").type,
    },
  ]);
  const second = await postEdits(request, first, "bob", [
    { kind: "remove_support", child: "o3" },
    { kind: "remove_object", id: "o2" },
    { kind: "set_class", id: "o0", class: "sofa" },
  ]);

  await openScene(page, seeded.scene_id);
  await setAuthor(page, "e2e-history");
  await page.keyboard.press("Shift+H");
  await expect(page.getByTestId("revision-list")).toBeVisible();

  // Diff of alice's revision: o1 moved, o2's guess confirmed.
  await page.getByTestId(`revision-diff-button-${first.revision}`).click();
  const diff = page.getByTestId(`revision-diff-${first.revision}`);
  await expect(diff.locator("li[data-child='o1']")).toHaveAttribute("data-kind", "moved");
  await expect(diff.locator("li[data-child='o1']")).toContainText("→ on o0 (below, by alice)");
  await expect(diff.locator("li[data-child='o2']")).toHaveAttribute("data-kind", "confirmed");
  await page.getByTestId(`revision-diff-button-${second.revision}`).click();
  await expect(
    page.getByTestId(`revision-diff-${second.revision}`).locator("li[data-child='o3']"),
  ).toHaveAttribute("data-kind", "removed");
  // "Since" lists everything from the pipeline's revision to now in one list: alice's move and
  // bob's removals and class change.
  await page.getByTestId(`revision-since-button-${predicted}`).click();
  const since = page.getByTestId(`revision-diff-${predicted}`);
  await expect(since.locator("li[data-child='o1']")).toHaveAttribute("data-kind", "moved");
  await expect(since).toContainText("objects removed: o2");
  await expect(since.locator("li[data-object='o0']")).toContainText("class");
  // Each object a line names selects it on the photo; a removed one is struck through.
  await since.locator("li[data-object='o0'] .object-id-link", { hasText: "o0" }).click();
  await expect(page.getByTestId("mask-o0")).toHaveClass(/is-selected/);
  await expect(since.locator("li[data-child='o2'] del", { hasText: "o2" }).first()).toBeVisible();
  await page.screenshot({ path: screenshotPath("revision-diff.png"), fullPage: true });

  // Revert to the pipeline's revision: the whole scene as the pipeline stored it (bob's removed
  // dresser and his sofa too, not only the supports).
  await page.getByTestId(`revision-revert-${predicted}`).click();
  const latest = async () => (await getScene(request, seeded.scene_id)).revision;
  await expect.poll(latest).toBe(second.revision + 1);
  let doc = await getScene(request, seeded.scene_id);
  expect(doc.scene).toEqual(seeded.scene);
  await expect(page.getByTestId("object-edit-status")).toContainText(
    `Revert to revision ${predicted}: saved.`,
  );
  await expect(page.getByTestId("object-row-o2")).toBeVisible();
  await expect(page.getByTestId("revision-list").locator("li").first()).toContainText(
    `the scene as in revision ${predicted}`,
  );

  // Undo the revert: bob's and alice's changes come back as they were.
  await page.keyboard.press("Control+z");
  await expect.poll(latest).toBe(second.revision + 2);
  doc = await getScene(request, seeded.scene_id);
  expect(doc.scene).toEqual(second.scene);

  // Bob saves again, unseen by this page: a revert now is not applied on top of his revision.
  const third = await postEdits(request, doc, "bob", [
    { kind: "set_class", id: "o1", class: "desk" },
  ]);
  await page.getByTestId(`revision-revert-${predicted}`).click();
  await expect(page.getByTestId("object-edit-status")).toContainText(
    `bob saved revision ${third.revision} meanwhile; reverting now would throw their change away`,
  );
  expect((await getScene(request, seeded.scene_id)).revision).toBe(third.revision);
});

test("two people edit one scene: the second gets a conflict, merges or reloads, nothing is lost", async ({
  browser,
  request,
}) => {
  const seeded = await seedScene(request, T3D_5, "t3d-5 two people");
  const alice = await (await browser.newContext()).newPage();
  const bob = await (await browser.newContext()).newPage();
  await openScene(alice, seeded.scene_id);
  await openScene(bob, seeded.scene_id);
  await setAuthor(alice, "alice");
  await setAuthor(bob, "bob");

  // Alice moves o1 onto o0 and it autosaves.
  await clickArrow(alice, "o1");
  await clickObject(alice, "o0");
  await autosaved(alice);

  // Bob, still on the revision he loaded, changes o1 too, and o3: his autosave conflicts.
  await clickArrow(bob, "o1");
  await bob.keyboard.press("f");
  await clickArrow(bob, "o3");
  await bob.keyboard.press("w");
  const conflict = bob.getByTestId("conflict-message");
  await expect(conflict).toBeVisible({ timeout: 20_000 });
  await expect(conflict).toContainText("alice saved this scene");
  await expect(bob.getByTestId("conflict-theirs")).toContainText("by alice");
  await expect(bob.getByTestId("pending-edits")).toContainText("o3: on wall");
  await bob.screenshot({ path: screenshotPath("conflict-two-people.png"), fullPage: true });

  // Merge (Shift+M): bob's edits saved on top of alice's, and he is told about o1.
  await bob.keyboard.press("Shift+M");
  await autosaved(bob);
  await expect(conflict).toBeHidden();
  await expect(bob.getByTestId("reload-notice")).toContainText("Both of you changed o1");
  let doc = await getScene(request, seeded.scene_id);
  expect(supportOf(doc, "o1")).toMatchObject({ parent: "floor", author: "bob" });
  expect(supportOf(doc, "o3")).toMatchObject({ parent: "wall", author: "bob" });
  // Alice's edit is not lost: it is a revision of its own.
  const revisions = await getRevisions(request, seeded.scene_id);
  expect(
    revisions.some((r) => r.author === "alice" && r.summary.includes("o1 supported by o0")),
  ).toBe(true);

  // Now Alice is behind. Her next edit is of o3, which Bob changed too: it conflicts, and
  // she reloads to review first.
  await clickArrow(alice, "o3");
  await clickObject(alice, "o0");
  await expect(alice.getByTestId("conflict-message")).toBeVisible({ timeout: 20_000 });
  await alice.getByTestId("conflict-reload").click();
  await expect(alice.getByTestId("conflict-message")).toBeHidden();
  await expect(alice.getByTestId("reload-notice")).toContainText("by bob");
  await expect(alice.getByTestId("reload-notice")).toContainText("Both of you changed o3");
  // Bob's change is shown, hers is kept unsaved until she saves.
  await expect(alice.getByTestId("arrow-o1")).toHaveAttribute("data-parent", "floor");
  await expect(alice.getByTestId("arrow-o3")).toHaveAttribute("data-pending", "true");
  await alice.waitForTimeout(3000); // longer than the autosave delay: held for her review
  await expect(alice.getByTestId("save-status")).toHaveAttribute("data-state", "dirty");
  await expect(alice.getByTestId("save-status")).toContainText("review, then Save (Ctrl+S)");
  await alice.keyboard.press("Control+s");
  await autosaved(alice);
  doc = await getScene(request, seeded.scene_id);
  expect(supportOf(doc, "o3")).toMatchObject({ parent: "o0", author: "alice" });
  expect(supportOf(doc, "o1")).toMatchObject({ parent: "floor", author: "bob" });
});
