// User story: an annotator fixes objects the pipeline got wrong. Shift+C opens the class
// picker on the selected object (its class listed first) and the new class is saved at once;
// Delete removes an object with its mask and every support it took part in; Ctrl+Z takes
// either back exactly, and Ctrl+Shift+Z does it again.
import type { SceneDocument } from "@holiscene/schema";
import { expect, type Page, test } from "@playwright/test";
import { getScene, seedScene, T3D_5 } from "../helpers/api";
import { chooseTool, objectEditsSaved } from "../helpers/objects";
import { arrowOf, clickObject, openScene, slowAutosave } from "../helpers/photo";
import { screenshotPath } from "../helpers/screenshots";

const objectOf = (doc: SceneDocument, id: string) => doc.scene.objects?.find((o) => o.id === id);
const supportsOf = (doc: SceneDocument, id: string) =>
  (doc.scene.supports ?? []).filter((s) => s.child === id || s.parent === id);

type Timed = Window & { redrawn?: Promise<number> };

/** Milliseconds from pressing `key` until `selector` is (or is no longer) on the page. */
async function timeTo(page: Page, key: string, selector: string, present: boolean) {
  // Listening before the key is sent (an evaluate not awaited may arrive after it).
  await page.evaluate(
    ({ selector, present }) => {
      (window as Timed).redrawn = new Promise<number>((resolve) => {
        // From the key's arrival in the page to the photo's SVG showing the change (the
        // frame on screen may come later while the 3D view renders, in software here).
        const onKey = (event: KeyboardEvent) => {
          if (["Control", "Shift", "Alt", "Meta"].includes(event.key)) return;
          window.removeEventListener("keydown", onKey, true);
          const start = event.timeStamp;
          const observer = new MutationObserver(() => {
            if ((document.querySelector(selector) !== null) !== present) return;
            observer.disconnect();
            resolve(performance.now() - start);
          });
          observer.observe(document.body, { subtree: true, childList: true });
        };
        window.addEventListener("keydown", onKey, true);
      });
    },
    { selector, present },
  );
  await page.keyboard.press(key);
  return page.evaluate(() => (window as Timed).redrawn as Promise<number>);
}

/** Wait until the server's latest revision is `revision`, and return it. */
async function revisionSaved(page: Page, sceneId: string, revision: number) {
  await objectEditsSaved(page);
  await expect.poll(async () => (await getScene(page.request, sceneId)).revision).toBe(revision);
  return getScene(page.request, sceneId);
}

test("a class changed with the picker, and an object deleted, come back with undo and from the history", async ({
  page,
  request,
}) => {
  const seeded = await seedScene(request, T3D_5, "t3d-5 class and delete");
  const sceneId = seeded.scene_id;
  const start = seeded.revision;
  await slowAutosave(page); // a support edit stays unsaved (undone without a revision)
  await openScene(page, sceneId);
  // The box tool selects what is clicked, as the select tool does.
  await chooseTool(page, "box");

  // Shift+C on the selected dresser: the picker lists its class first.
  const dresser = (seeded.scene.objects ?? []).find((o) => o.class === "dresser");
  if (!dresser) throw new Error("t3d-5 has a dresser");
  await clickObject(page, dresser.id);
  await expect(page.getByTestId("box-tool-selected")).toHaveCount(1);
  // Esc closes the picker and changes nothing.
  await page.keyboard.press("Shift+C");
  await expect(page.getByTestId("class-picker")).toBeVisible();
  await page.keyboard.press("Escape");
  await expect(page.getByTestId("class-picker")).toHaveCount(0);
  await expect(page.getByTestId("box-tool-selected")).toHaveCount(1);
  await page.keyboard.press("Shift+C");
  await expect(page.getByTestId("class-option").first()).toHaveAttribute("data-name", "dresser");
  await page.getByTestId("class-picker-input").fill("sh");
  await page.screenshot({ path: screenshotPath("class-picker-change.png") });
  // ↓ moves to the second line (shower curtain), ↑ back; Enter picks.
  const input = page.getByTestId("class-picker-input");
  await input.press("ArrowDown");
  await expect(page.locator('[data-testid="class-option"].is-active')).toHaveAttribute(
    "data-name",
    "shower_curtain",
  );
  await input.press("ArrowUp");
  await input.press("Enter");
  await expect(page.getByTestId("class-picker")).toHaveCount(0);
  let doc = await revisionSaved(page, sceneId, start + 1);
  expect(objectOf(doc, dresser.id)?.class).toBe("shelves");
  // The keyboard goes back where it was (the Box tool's button), not to the page's start.
  await expect(page.getByTestId("photo-tool-box")).toBeFocused();
  await expect(page.getByTestId("undo-button")).toHaveAttribute(
    "title",
    /Undo: dresser .* → shelves/,
  );

  // Ctrl+Z: the class is back, exactly as it was; Ctrl+Shift+Z sets it again.
  await page.keyboard.press("Control+z");
  doc = await revisionSaved(page, sceneId, start + 2);
  expect(objectOf(doc, dresser.id)).toEqual(objectOf(seeded, dresser.id));
  await page.keyboard.press("Control+Shift+z");
  doc = await revisionSaved(page, sceneId, start + 3);
  expect(objectOf(doc, dresser.id)?.class).toBe("shelves");

  // One undo for the page: after a support edit, Ctrl+Z takes that back first, and the class
  // change is next.
  const supporter = (await arrowOf(page, dresser.id))?.parent;
  await page.keyboard.press("w");
  await expect.poll(async () => (await arrowOf(page, dresser.id))?.parent).toBe("wall");
  await page.keyboard.press("Control+z");
  await expect.poll(async () => (await arrowOf(page, dresser.id))?.parent).toBe(supporter);
  await expect(page.locator(`tr[data-object="${dresser.id}"]`)).toContainText("shelves");
  await expect(page.getByTestId("undo-button")).toHaveAttribute(
    "title",
    /Undo: dresser .* → shelves/,
  );

  // Delete an object that takes part in supports (a supporter if there is one).
  const supports = doc.scene.supports ?? [];
  const target =
    supports.find((s) => !["floor", "wall", "ceiling"].includes(s.parent))?.parent ??
    supports[0]?.child;
  if (!target) throw new Error("the pipeline gave t3d-5 supports");
  const before = doc;
  expect(supportsOf(before, target).length).toBeGreaterThan(0);
  await clickObject(page, target);
  // How long a person waits from the key to the photo without the object (saved first).
  // The server's answers are held back a while: the photo is redrawn before they come.
  const HOLD_MS = 1500;
  const edits = `**/api/scenes/${sceneId}/edits`;
  await page.route(edits, async (route) => {
    await new Promise((resolve) => setTimeout(resolve, HOLD_MS));
    await route.continue();
  });
  const gone = await timeTo(page, "Delete", `[data-testid="mask-${target}"]`, false);
  doc = await revisionSaved(page, sceneId, start + 4);
  expect(objectOf(doc, target)).toBeUndefined();
  expect(supportsOf(doc, target)).toEqual([]);
  await expect(page.getByTestId(`mask-${target}`)).toHaveCount(0);
  await expect(page.locator(`tr[data-object="${target}"]`)).toHaveCount(0);

  // Undo brings the object, its mask and every support it took part in back.
  const back = await timeTo(page, "Control+z", `[data-testid="mask-${target}"]`, true);
  doc = await revisionSaved(page, sceneId, start + 5);
  expect(objectOf(doc, target)).toEqual(objectOf(before, target));
  expect(supportsOf(doc, target)).toEqual(supportsOf(before, target));
  await expect(page.getByTestId(`mask-${target}`)).toHaveCount(1);
  await expect(page.locator(`tr[data-object="${target}"]`)).toBeVisible();
  await expect(page.getByTestId("object-edit-status")).toContainText("Undo remove");
  await page.unroute(edits);
  // Drawn long before the answer could come. The target is 50 ms: 16-49 ms measured on the
  // 2-core test machine when lightly loaded, 70-131 ms at a load average of 10.
  console.log(`delete to redrawn ${gone.toFixed(0)} ms, undo to redrawn ${back.toFixed(0)} ms`);
  expect(gone).toBeLessThan(HOLD_MS / 2);
  expect(back).toBeLessThan(HOLD_MS / 2);

  // Deleted again, with the mouse this time (the selected object's "remove" in the tool hint),
  // and the page reloaded (its undo history gone): the revision history's diff of that
  // deletion brings the one object back, supports and all, changing nothing else.
  await page.getByRole("button", { name: "Select", exact: true }).click();
  await clickObject(page, target);
  const hint = page.getByTestId("selected-object-hint");
  await expect(hint).toContainText(`${target}: remove (Delete) · change class (Shift+C)`);
  await hint.getByTestId("remove-selected-object").click();
  await expect(page.getByTestId("selected-object-hint")).toHaveCount(0);
  doc = await revisionSaved(page, sceneId, start + 6);
  expect(objectOf(doc, target)).toBeUndefined();
  await page.reload();
  await expect(page.getByTestId("photo")).toHaveAttribute("data-loaded", "true");
  await page.getByTestId("history-toggle").click();
  await page.getByTestId(`revision-diff-button-${start + 6}`).click();
  const diff = page.getByTestId(`revision-diff-${start + 6}`);
  await expect(diff).toContainText(`objects removed: ${target}`);
  await diff.getByTestId(`restore-object-${target}`).click();
  doc = await revisionSaved(page, sceneId, start + 7);
  expect(objectOf(doc, target)).toEqual(objectOf(before, target));
  expect(supportsOf(doc, target)).toEqual(supportsOf(before, target));
  expect(objectOf(doc, dresser.id)?.class).toBe("shelves"); // the later change stays
  await expect(page.getByTestId(`mask-${target}`)).toHaveCount(1);
});

test("an object named by another dataset's word gets the plain class when that is picked", async ({
  page,
  request,
}) => {
  const seeded = await seedScene(request, T3D_5, "t3d-5 plain class");
  const sceneId = seeded.scene_id;
  await openScene(page, sceneId);
  const dresser = (seeded.scene.objects ?? []).find((o) => o.class === "dresser");
  if (!dresser) throw new Error("t3d-5 has a dresser");
  await clickObject(page, dresser.id);
  const pick = async (typed: string, expected: string) => {
    await page.keyboard.press("Shift+C");
    await page.getByTestId("class-picker-input").fill(typed);
    await expect(page.getByTestId("class-option").first()).toHaveAttribute("data-name", expected);
    await page.getByTestId("class-picker-input").press("Enter");
    await expect(page.getByTestId("class-picker")).toHaveCount(0);
  };
  // Another dataset's word for a chair: stored as chair, the word kept beside it.
  await pick("sofa chair", "sofa_chair");
  let doc = await revisionSaved(page, sceneId, seeded.revision + 1);
  expect(objectOf(doc, dresser.id)).toMatchObject({ class: "chair", source_class: "sofa_chair" });
  await expect(page.locator(`tr[data-object="${dresser.id}"]`)).toContainText("chair (sofa_chair)");
  // The plain class then is a change: the word goes (it was a silent no-op).
  await pick("chair", "chair");
  doc = await revisionSaved(page, sceneId, seeded.revision + 2);
  expect(objectOf(doc, dresser.id)?.class).toBe("chair");
  expect(objectOf(doc, dresser.id)?.source_class ?? null).toBeNull();
  await expect(page.locator(`tr[data-object="${dresser.id}"]`)).not.toContainText("sofa_chair");
});
