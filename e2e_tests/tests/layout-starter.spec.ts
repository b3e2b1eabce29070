// User story: the pipeline found no room in a photo (too few straight lines for pitch and
// roll). The annotator presses "Edit layout", gets a room to start from with its back corners
// on the photo, drags one onto the photo's room, and saves: the scene has a hand-set room and
// a camera pitch and roll, and the layout stage's warning says so. Putting up the starting
// room alone saves nothing.
import type { SceneSummary } from "@holiscene/schema";
import { expect, test } from "@playwright/test";
import { getRevisions, getScene, waitForJob } from "../helpers/api";
import { layoutProbe } from "../helpers/scene3d";
import { screenshotPath } from "../helpers/screenshots";

test("a photo without a room: editing starts one, and a dragged corner saves it", async ({
  page,
  request,
}) => {
  test.setTimeout(180_000);
  // A smooth gradient: no line for the layout stage to find.
  await page.goto("/");
  const dataUrl = await page.evaluate(() => {
    const canvas = document.createElement("canvas");
    canvas.width = 640;
    canvas.height = 480;
    const context = canvas.getContext("2d");
    if (!context) throw new Error("no 2D canvas");
    const gradient = context.createLinearGradient(0, 0, 640, 480);
    gradient.addColorStop(0, "#9a8c82");
    gradient.addColorStop(1, "#c2b0a0");
    context.fillStyle = gradient;
    context.fillRect(0, 0, 640, 480);
    return canvas.toDataURL("image/png");
  });
  const response = await request.post("/api/scenes", {
    multipart: {
      image: {
        name: "img.png",
        mimeType: "image/png",
        buffer: Buffer.from(dataUrl.split(",")[1] ?? "", "base64"),
      },
      cam_k: {
        name: "cam_K.txt",
        mimeType: "text/plain",
        buffer: Buffer.from("500 0 320\n0 500 240\n0 0 1\n"),
      },
      detections: {
        name: "detections.json",
        mimeType: "application/json",
        buffer: Buffer.from("[]"),
      },
      name: "no room found",
    },
  });
  expect(response.status(), await response.text()).toBe(201);
  const imported = (await response.json()) as { scene: SceneSummary; job: { id: string } | null };
  const sceneId = imported.scene.id;
  if (imported.job) expect((await waitForJob(request, imported.job.id)).status).toBe("succeeded");
  const before = await getScene(request, sceneId);
  expect(before.scene.camera?.pitch_deg ?? null).toBeNull();
  expect(before.scene.layout?.corners_3d ?? null).toBeNull();
  const revisions = (await getRevisions(request, sceneId)).length;

  await page.goto(`/#/scenes/${sceneId}`);
  const status = page.getByTestId("layout-status");
  await expect(status).toContainText('No room layout yet: "Edit layout" puts up a room');
  const toggle = page.getByTestId("layout-toggle");
  await expect(toggle).toBeEnabled();
  await expect(page.getByTestId("replace-objects")).toBeDisabled(); // no room to place in

  // The starting room: a level camera, the back wall's four corners as handles.
  await toggle.click();
  await expect(status).toContainText("A room to start from");
  const live = await layoutProbe(page, (p) => p.live());
  expect(live?.pitchDeg).toBe(0);
  const handles = page.locator("[data-testid^='layout-handle-'][data-pinned='true']");
  await expect(handles).toHaveCount(4);
  await expect(page.getByTestId("layout-save")).toBeDisabled(); // nothing moved yet
  // Stopping untouched takes it away again, and nothing was saved.
  await toggle.click();
  expect(await layoutProbe(page, (p) => p.live())).toBeNull();
  await expect(page.getByTestId("layout-layer")).toBeHidden();
  await toggle.click();

  // Drag the back wall's top right corner a little up and out, then save.
  const corner = page.getByTestId("layout-handle-6");
  await corner.scrollIntoViewIfNeeded();
  const box = await corner.boundingBox();
  if (!box) throw new Error("corner 6 has no handle on the screen");
  const [x, y] = [box.x + box.width / 2, box.y + box.height / 2];
  await page.mouse.move(x, y);
  await page.mouse.down();
  await page.mouse.move(x + 20, y - 15, { steps: 5 });
  await page.mouse.up();
  await expect(status).toContainText("Moved (not saved)");
  await page.getByTestId("layout-save").click();
  await expect(status).toContainText("Layout saved");
  // The layout stage's warning says the room it could not find was set by hand since.
  await expect(page.getByTestId("pipeline-warnings")).toContainText(
    "too few vertical lines: pitch, roll and layout unknown (the room has since been set by hand)",
  );
  await page.screenshot({ path: screenshotPath("layout-starter.png") });

  const after = await getScene(request, sceneId);
  expect(after.scene.layout?.source).toBe("manual");
  expect(after.scene.layout?.corners_3d).toHaveLength(8);
  expect(after.scene.camera?.pitch_deg).not.toBeNull();
  expect(after.scene.camera?.roll_deg).not.toBeNull();
  expect((await getRevisions(request, sceneId)).length).toBe(revisions + 1);
  await expect(page.getByTestId("replace-objects")).toBeEnabled();
});
