// User story: two annotators edit objects of one scene at the same time. Each object action is
// saved at once on the revision its page has loaded; when the other saved first, the page
// loads their revision and applies the action on top of it, and says so. An action on an
// object the other removed cannot be applied: it stays on screen with Retry and Discard (after
// a reload too), so nothing anyone did is lost without them knowing.
import type { SceneDocument } from "@holiscene/schema";
import { type Browser, expect, type Page, test } from "@playwright/test";
import { getScene, seedScene, T3D_5 } from "../helpers/api";
import { chooseTool, objectEditsSaved, pickClass } from "../helpers/objects";
import { clickObject, openScene, setAuthor } from "../helpers/photo";
import { screenshotPath } from "../helpers/screenshots";

const classOf = (doc: SceneDocument, id: string) =>
  doc.scene.objects?.find((o) => o.id === id)?.class;

async function annotator(browser: Browser, name: string, sceneId: string): Promise<Page> {
  const page = await (await browser.newContext()).newPage();
  await page.goto("/#/");
  await setAuthor(page, name);
  await openScene(page, sceneId);
  await chooseTool(page, "box");
  return page;
}

async function changeClass(page: Page, id: string, typed: string, name: string): Promise<void> {
  await clickObject(page, id);
  await page.keyboard.press("Shift+C");
  await pickClass(page, typed, name);
}

test("two people editing objects at once: the second is told, and nothing is lost", async ({
  browser,
  request,
}) => {
  const seeded = await seedScene(request, T3D_5, "t3d-5 two annotators");
  const sceneId = seeded.scene_id;
  const start = seeded.revision;
  const [o0, o1, o2, o3] = (seeded.scene.objects ?? []).map((o) => o.id);
  if (!o0 || !o1 || !o2 || !o3) throw new Error("t3d-5 has four objects");
  const alice = await annotator(browser, "alice", sceneId);
  const bob = await annotator(browser, "bob", sceneId);

  // Alice saves first; Bob's page still has the revision both loaded.
  await changeClass(alice, o2, "desk", "desk");
  await objectEditsSaved(alice);
  await changeClass(bob, o3, "cabin", "cabinet");
  await objectEditsSaved(bob);
  const bobStatus = bob.getByTestId("object-edit-status");
  await expect(bobStatus).toHaveText(
    `alice saved revision ${start + 1} meanwhile; your change was applied on top.`,
  );
  let doc = await getScene(request, sceneId);
  expect(doc.revision).toBe(start + 2);
  expect(classOf(doc, o2)).toBe("desk");
  expect(classOf(doc, o3)).toBe("cabinet");
  // Bob's page shows both changes.
  await expect(bob.locator(`tr[data-object="${o2}"]`)).toContainText("desk");

  // Now Alice is behind: she removes the night stand on top of Bob's revision.
  await clickObject(alice, o1);
  await alice.keyboard.press("Delete");
  await objectEditsSaved(alice);
  await expect(alice.getByTestId("object-edit-status")).toContainText(
    `bob saved revision ${start + 2} meanwhile`,
  );

  // Bob, who still sees the night stand, renames it: it is gone, so his change is kept on
  // screen with the reason, Retry and Discard. His Box tool is still in hand (Alice's saves
  // never lock his page, not even for a moment).
  await expect(bob.getByTestId("photo-tool-box")).toHaveAttribute("aria-pressed", "true");
  await changeClass(bob, o1, "dress", "dresser");
  const failure = bob.getByTestId("object-edit-failure");
  await expect(failure).toBeVisible();
  await expect(bob.getByTestId("object-edit-failure-text")).toContainText(
    `alice saved revision ${start + 3} meanwhile, and ${o1} is no longer in the scene`,
  );
  await expect(bob.getByTestId("object-edit-failure-text")).toContainText("dresser");
  await expect(bob.getByTestId("object-edit-retry")).toBeVisible();
  await bob.screenshot({ path: screenshotPath("object-edit-conflict.png") });
  // His page shows the latest revision: the night stand is gone there too.
  await expect(bob.getByTestId(`mask-${o1}`)).toHaveCount(0);
  doc = await getScene(request, sceneId);
  expect(doc.revision).toBe(start + 3);
  expect(doc.scene.objects?.some((o) => o.id === o1)).toBe(false);
  expect(classOf(doc, o3)).toBe("cabinet");

  // Closing the tab (a reload here) loses nothing: the next visit offers it again.
  const failureText = bob.getByTestId("object-edit-failure-text");
  await bob.reload();
  await expect(bob.getByTestId("photo")).toHaveAttribute("data-loaded", "true");
  await expect(failure).toBeVisible();
  await expect(failureText).toContainText(`${o1} is no longer in the scene`);
  await expect(failureText).toContainText("Not saved on your last visit");
  await expect(failureText).toContainText("dresser");
  await expect(bob.getByTestId("object-edit-retry")).toBeVisible();
  await bob.screenshot({ path: screenshotPath("object-edit-failure-kept.png") });

  // Discard is his choice; the message goes, and stays gone after another reload.
  await bob.getByTestId("object-edit-discard").click();
  await expect(failure).toBeHidden();
  await expect(bobStatus).toContainText("Dropped:");
  await bob.reload();
  await expect(bob.getByTestId("photo")).toHaveAttribute("data-loaded", "true");
  await expect(bob.getByTestId("object-edit-bar")).toBeAttached();
  await expect(failure).toBeHidden();
  expect((await getScene(request, sceneId)).revision).toBe(start + 3);
});
