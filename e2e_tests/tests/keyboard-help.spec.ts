// User story: keyboard first. Every editing action has a shortcut, and "?" opens a list of
// every shortcut registered on the page (the registry writes the list, so a key cannot work
// without being listed); Escape or "?" closes it.
import { expect, type Page, test } from "@playwright/test";
import { seedScene, T3D_5 } from "../helpers/api";
import { openScene } from "../helpers/photo";
import { screenshotPath } from "../helpers/screenshots";

// The actions of support editing, live suggestions, object suggestions, object editing, the
// photo's tools and zoom, and no-lost-work, by their keys.
const SCENE_KEYS: Record<string, string> = {
  A: "accept the selected edge",
  "Shift+A": "accept every remaining edge",
  R: "reject the selected edge",
  T: "flip below/behind",
  "Shift+Delete Shift+Backspace": "remove the supporter",
  Delete: "remove the selected object",
  "Shift+C": "change the selected object's class",
  V: "the select tool",
  B: "the box tool",
  "+ =": "zoom in",
  "-": "zoom out",
  "0": "fit the photo",
  Space: "pan the photo",
  F: "floor",
  W: "wall",
  C: "ceiling",
  N: "next object to check",
  "Shift+N": "previous object to check",
  Escape: "clear the selection",
  H: "hide or show the arrows",
  M: "hide or show the masks",
  L: "hide or show the labels",
  "Ctrl+Z": "undo",
  "Ctrl+Shift+Z Ctrl+Y": "redo",
  "Ctrl+S": "save now",
  "Shift+M": "merge after a conflict",
  "Shift+R": "reload after a conflict",
  "Shift+U": "restore unsaved changes",
  "Shift+H": "revision history",
  D: "detect objects",
  Y: "accept the selected suggested box",
  "Shift+Y": "accept every suggested box",
  X: "reject the selected suggested box",
  "?": "this list",
};

/** The help's rows (those on now only): keys ("A", "Ctrl+Shift+Z Ctrl+Y") and text. */
function listedRows(page: Page, onlyOn = false): Promise<(readonly [string, string])[]> {
  const all = page.getByTestId("shortcut-help").getByTestId("shortcut-row");
  const rows = onlyOn ? all.and(page.locator('[data-enabled="true"]')) : all;
  return rows.evaluateAll((nodes) =>
    nodes.map((n) => [(n as HTMLElement).dataset.keys ?? "", n.textContent ?? ""] as const),
  );
}

async function listed(page: Page): Promise<Map<string, string>> {
  return new Map(await listedRows(page));
}

test("? lists every shortcut of the scene page, and Escape closes the list", async ({
  page,
  request,
}) => {
  const seeded = await seedScene(request, T3D_5, "t3d-5 keys");
  await openScene(page, seeded.scene_id);
  const help = page.getByTestId("shortcut-help");
  await expect(help).toBeHidden();

  await page.keyboard.press("?");
  await expect(help).toBeVisible();
  const rows = await listed(page);
  for (const [keys, action] of Object.entries(SCENE_KEYS)) {
    expect(rows.has(keys), `${keys} (${action}) is listed`).toBe(true);
    expect((rows.get(keys) ?? "").length, `${keys} has a description`).toBeGreaterThan(
      keys.length + 5,
    );
  }
  // Grouped by what they act on.
  for (const scope of [
    "Support editing",
    "Saving and history",
    "Photo",
    "Object suggestions",
    "General",
  ]) {
    await expect(help.locator(`section[data-scope="${scope}"]`)).toBeVisible();
  }
  // One key never means two things on the page at once (Escape aside: it always closes or
  // cancels the innermost thing open, the help itself first).
  const owners = new Map<string, string[]>();
  for (const [keys, text] of await listedRows(page, true)) {
    for (const key of keys.split(" ")) owners.set(key, [...(owners.get(key) ?? []), text]);
  }
  const twice = [...owners].filter(([key, texts]) => key !== "Escape" && texts.length > 1);
  expect(twice, "keys with two meanings").toEqual([]);
  await page.screenshot({ path: screenshotPath("keyboard-help.png") });

  await page.keyboard.press("Escape");
  await expect(help).toBeHidden();
  await page.keyboard.press("?");
  await expect(help).toBeVisible();
  await page.keyboard.press("?");
  await expect(help).toBeHidden();

  // The keys are live while listed: N selects an object, H hides the arrows.
  await page.keyboard.press("n");
  await expect(page.getByTestId("edge-info-edge")).toContainText(/^o\d/);
  await page.keyboard.press("h");
  await expect(page.getByTestId("arrow-layer")).toBeHidden();

  // Typing in a text field is typing, not shortcuts.
  await page.getByTestId("author-input").fill("");
  await page.getByTestId("author-input").pressSequentially("harry?");
  await expect(page.getByTestId("author-input")).toHaveValue("harry?");
  await expect(help).toBeHidden();
  await expect(page.getByTestId("arrow-layer")).toBeHidden();
});

test("leaving the scene page takes its shortcuts out of the list", async ({ page, request }) => {
  const seeded = await seedScene(request, T3D_5, "t3d-5 keys list");
  await openScene(page, seeded.scene_id);
  await page.goto("/#/");
  await expect(page.getByTestId("scene-list")).toBeVisible();
  await page.keyboard.press("?");
  const rows = await listed(page);
  expect(rows.has("?")).toBe(true);
  for (const keys of ["A", "Shift+A", "Ctrl+Z", "H"]) expect(rows.has(keys), keys).toBe(false);
});
