// User story: keyboard first. Every editing action has a shortcut, and "?" opens a list of
// every shortcut registered on the page (the registry writes the list, so a key cannot work
// without being listed); Escape or "?" closes it.
import { mkdirSync } from "node:fs";
import path from "node:path";
import { expect, type Page, test } from "@playwright/test";
import { seedScene, T3D_5 } from "../helpers/api";
import { openScene } from "../helpers/photo";

const SCREENSHOTS = path.resolve(import.meta.dirname, "../screenshots");
mkdirSync(SCREENSHOTS, { recursive: true });

// The actions of support editing, live suggestions, object suggestions and no-lost-work, by
// their keys.
const SCENE_KEYS: Record<string, string> = {
  A: "accept the selected edge",
  "Shift+A": "accept every remaining edge",
  R: "reject the selected edge",
  T: "flip below/behind",
  "Delete Backspace": "remove the supporter",
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

async function listed(page: Page): Promise<Map<string, string>> {
  const rows = page.getByTestId("shortcut-help").getByTestId("shortcut-row");
  const entries = await rows.evaluateAll((nodes) =>
    nodes.map((n) => [(n as HTMLElement).dataset.keys ?? "", n.textContent ?? ""] as const),
  );
  return new Map(entries);
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
  await page.screenshot({ path: path.join(SCREENSHOTS, "keyboard-help.png") });

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
