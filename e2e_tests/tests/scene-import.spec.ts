// User story: an annotator imports a photo with its intrinsics and detections, follows the
// pipeline's progress and opens the new scene.
import { mkdirSync, readFileSync, writeFileSync } from "node:fs";
import path from "node:path";
import type { ImportResult, Job, SceneSummary } from "@holiscene/schema";
import { expect, type Page, test } from "@playwright/test";
import { getScene, seedScene, T3D_5, waitForJob } from "../helpers/api";
import { submitUploadAndWait } from "../helpers/photo";

async function listScenes(page: Page): Promise<SceneSummary[]> {
  return (await (await page.request.get("/api/scenes")).json()) as SceneSummary[];
}

const scenesNamed = (scenes: SceneSummary[], name: string) => scenes.find((s) => s.name === name);

test("imports a photo through the form and opens the scene", async ({ page }) => {
  await page.goto("/#/");
  await expect(page.getByTestId("upload-form")).toBeVisible();
  await page.getByTestId("upload-image").setInputFiles(path.join(T3D_5, "img.jpg"));
  await page.getByTestId("upload-cam_k").setInputFiles(path.join(T3D_5, "cam_K.txt"));
  await page.getByTestId("upload-detections").setInputFiles(path.join(T3D_5, "detections.json"));
  // A dataset folder's photo is called img.jpg, like every other: the name suggested adds
  // the time ("img of 7 Dec, 10:53:12"); one typed replaces it.
  const name = page.getByTestId("upload-name");
  await expect(name).toHaveValue(/^img of .*\d\d:\d\d:\d\d/);
  await expect(page.getByTestId("upload-name-hint")).toContainText("every dataset folder");
  await name.fill("t3d-5 upload");
  await submitUploadAndWait(page);
  await expect(name).toHaveValue("");
  // Once the pipeline has finished, Open is the card's next step, and Enter takes it.
  await expect(page.getByTestId("upload-open")).toHaveClass(/is-ready/);
  await expect(page.getByTestId("upload-open")).toBeFocused();
  await expect(page.getByTestId("scene-list")).toContainText("t3d-5 upload");
  // "Pipeline finished" comes with the count of the run's warnings, as the scene stores them.
  const scenes = (await (await page.request.get("/api/scenes")).json()) as SceneSummary[];
  const uploaded = scenes.find((s) => s.name === "t3d-5 upload");
  if (!uploaded) throw new Error("the upload made no scene");
  const stored = await getScene(page.request, uploaded.id);
  const warned = stored.scene.stages.filter((s) => s.warning && s.note).length;
  if (warned > 0)
    await expect(page.getByTestId("upload-warnings")).toContainText(
      `${warned} pipeline warning${warned === 1 ? "" : "s"}`,
    );
  else await expect(page.getByTestId("upload-warnings")).toHaveCount(0);
  const screenshots = path.resolve(import.meta.dirname, "../screenshots");
  mkdirSync(screenshots, { recursive: true });
  await page.screenshot({ path: path.join(screenshots, "scene-list.png"), fullPage: true });

  await page.keyboard.press("Enter");
  await expect(page.getByTestId("scene-title")).toHaveText("t3d-5 upload");
  await expect(page.getByTestId("mask-layer").locator("[data-testid^='mask-']")).toHaveCount(4);
  await expect(page.getByTestId("arrow-layer").locator("[data-testid^='arrow-']")).toHaveCount(4);

  // The same photo once more: imported (other labels for one photo are fine), and said.
  await page.goto("/#/");
  await page.getByTestId("upload-image").setInputFiles(path.join(T3D_5, "img.jpg"));
  await page.getByTestId("upload-name").fill("t3d-5 upload again");
  await page.getByTestId("upload-submit").click();
  // (Named by the first scene of the photo: in a full test run another spec's, imported
  // earlier.)
  const twin = page.getByTestId("upload-same-photo");
  await expect(twin).toContainText("This very photo was imported before, as ");
  await expect(twin).toContainText('"t3d-5 upload again" is a second scene of it.');
  const firstId = ((await twin.getByRole("link").getAttribute("href")) ?? "").replace(
    "#/scenes/",
    "",
  );
  const again = scenesNamed(await listScenes(page), "t3d-5 upload again");
  expect(firstId).not.toBe(again?.id);
  const photo = await (await page.request.get(`/api/scenes/${firstId}/image`)).body();
  expect(photo.equals(readFileSync(path.join(T3D_5, "img.jpg")))).toBe(true);
});

test("a scene whose pipeline is still running shows progress, then opens", async ({
  page,
  request,
}) => {
  const seeded = await seedScene(request, T3D_5, "t3d-5 running");
  const jobs = (await (await request.get("/api/scenes")).json()) as SceneSummary[];
  const jobId = jobs.find((s) => s.id === seeded.scene_id)?.latest_job?.id;
  if (!jobId) throw new Error("the seeded scene has no pipeline job");

  // The pipeline on this photo takes well under a second, too quick to watch: the page is
  // shown the job as still running for its first two looks at it.
  const running = { status: "running", progress: 0.4, stage: "supports" } as const;
  // The list, with or without its query (the scene page asks for archived scenes too).
  await page.route(/\/api\/scenes(\?[^/]*)?$/, async (route) => {
    const response = await route.fetch();
    const scenes = (await response.json()) as SceneSummary[];
    const json = scenes.map((s) =>
      s.id === seeded.scene_id && s.latest_job
        ? { ...s, latest_job: { ...s.latest_job, ...running } }
        : s,
    );
    await route.fulfill({ response, json });
  });
  let looks = 0;
  await page.route(`**/api/jobs/${jobId}`, async (route) => {
    const response = await route.fetch();
    const job = (await response.json()) as Job;
    looks += 1;
    await route.fulfill({ response, json: looks < 2 ? { ...job, ...running } : job });
  });

  await page.goto(`/#/scenes/${seeded.scene_id}`);
  const progress = page.getByTestId("job-progress");
  await expect(progress).toHaveAttribute("data-status", "running");
  await expect(progress).toContainText("supports");
  await expect(page.getByTestId("object-table")).toBeVisible();
  await expect(progress).toBeHidden();
  await expect(page.getByTestId("arrow-layer").locator("[data-testid^='arrow-']")).toHaveCount(4);
});

test("a scene without objects says so and shows the pipeline's warnings", async ({
  page,
  request,
}) => {
  // No cam_K.txt and an empty detections.json: the intrinsics are assumed, no object is given.
  const response = await request.post("/api/scenes", {
    multipart: {
      image: {
        name: "img.jpg",
        mimeType: "image/jpeg",
        buffer: readFileSync(path.join(T3D_5, "img.jpg")),
      },
      detections: {
        name: "detections.json",
        mimeType: "application/json",
        buffer: Buffer.from("[]"),
      },
      name: "t3d-5 without objects",
    },
  });
  expect(response.status(), await response.text()).toBe(201);
  const imported = (await response.json()) as ImportResult;
  if (!imported.job) throw new Error("the import started no pipeline job");
  expect((await waitForJob(request, imported.job.id)).status).toBe("succeeded");

  await page.goto(`/#/scenes/${imported.scene.id}`);
  const summary = page.getByTestId("support-summary");
  await expect(summary).toHaveText(/^No objects yet\. Accept the detector's suggested boxes/);
  await expect(summary).not.toContainText("supported");
  const warnings = page.getByTestId("pipeline-warnings");
  await expect(warnings).toBeVisible();
  await expect(
    warnings.getByTestId("pipeline-warning").filter({ hasText: "intrinsics" }),
  ).toContainText("no cam_K.txt");
  // The empty detections.json is said once; the stages after it do not blame the camera.
  await expect(
    warnings.getByTestId("pipeline-warning").filter({ hasText: "lists no objects" }),
  ).toHaveCount(1);
  await expect(warnings).not.toContainText("camera height");
  // A note that is no problem (the room's scale and where it came from) is not a warning.
  await expect(warnings).not.toContainText("scale from");
  // Open the first time; on the next visit folded to a line that names the stages.
  await expect(warnings).toHaveAttribute("open", "");
  await page.reload();
  await expect(page.getByTestId("pipeline-warnings-title")).toContainText("intrinsics");
  await expect(warnings).not.toHaveAttribute("open", "");
  await expect(warnings.getByTestId("pipeline-warning").first()).toBeHidden();
});

test("a dataset's own class names: a class map maps them, an unknown one is kept and flagged", async ({
  page,
}, testInfo) => {
  const dir = testInfo.outputPath("class-names");
  mkdirSync(dir, { recursive: true });
  const boxes = [
    { bbox: [40, 60, 300, 400], class: "doona" }, // the class map makes it a bed
    { bbox: [320, 200, 420, 330], class: "gadget" }, // in no vocabulary
  ];
  writeFileSync(path.join(dir, "detections.json"), JSON.stringify(boxes));
  writeFileSync(path.join(dir, "class_map.json"), JSON.stringify({ Doona: "bed" }));
  await page.goto("/#/");
  await page.getByTestId("upload-image").setInputFiles(path.join(T3D_5, "img.jpg"));
  await page.getByTestId("upload-detections").setInputFiles(path.join(dir, "detections.json"));
  await page.getByTestId("upload-class_map").setInputFiles(path.join(dir, "class_map.json"));
  await page.getByTestId("upload-name").fill("t3d-5 own class names");
  await submitUploadAndWait(page);
  await page.getByTestId("upload-open").click();
  await expect(page.getByTestId("object-row-o0")).toContainText("bed");
  // The dataset's own name stays beside the class it maps to.
  await expect(page.getByTestId("object-row-o1")).toContainText("otherprop (gadget)");
  const warning = page.getByTestId("pipeline-warning").filter({ hasText: "gadget" });
  await expect(warning).toContainText("class_map.json");
  await page.screenshot({ path: testInfo.outputPath("class-names.png"), fullPage: true });
});
