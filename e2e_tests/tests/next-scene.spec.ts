// User story: an annotator skips a scene with "Next scene" after looking at it: the scene they
// took and left as it was goes back to the queue, not kept as theirs with nobody on it; one
// they changed stays theirs.
import type { SceneDocument, SceneWorkflow } from "@holiscene/schema";
import { type APIRequestContext, expect, test } from "@playwright/test";
import { postEdits, seedScene, T3D_1, T3D_5 } from "../helpers/api";
import { screenshotPath } from "../helpers/screenshots";

async function workflowOf(request: APIRequestContext, sceneId: string): Promise<SceneWorkflow> {
  const response = await request.get(`/api/scenes/${sceneId}/workflow`);
  expect(response.status()).toBe(200);
  return (await response.json()) as SceneWorkflow;
}

test("Next scene gives back the scene taken and left untouched, and keeps one that was changed", async ({
  page,
  request,
}) => {
  const a = await seedScene(request, T3D_5, "next scene untouched");
  await seedScene(request, T3D_1, "next scene changed"); // one more scene to go on to
  // Taken from its page, looked at, skipped.
  await page.goto(`/#/scenes/${a.scene_id}`);
  await page.getByTestId("workflow-take").click();
  await expect(page.getByTestId("workflow-state")).toHaveText("in annotation");
  await page.getByTestId("next-scene").click();
  await expect(page).not.toHaveURL(new RegExp(`#/scenes/${a.scene_id}$`));
  await expect.poll(async () => (await workflowOf(request, a.scene_id)).state).toBe("predicted");
  expect((await workflowOf(request, a.scene_id)).events.at(-1)?.action).toBe("release");
  // The page it lands on says so, once.
  const said = page.getByTestId("next-scene-message");
  await expect(said).toHaveText(
    '"next scene untouched" went back to the queue: you took it and changed nothing.',
  );
  await expect(said).toBeVisible();
  await page.screenshot({ path: screenshotPath("next-scene-gave-back.png") });

  // The scene Next scene took: changed, then skipped, it stays the person's.
  const landed = /#\/scenes\/([^/]+)$/.exec(page.url())?.[1] ?? "";
  await expect(page.getByTestId("workflow-state")).toHaveText("in annotation");
  const taken = (await (await request.get(`/api/scenes/${landed}`)).json()) as SceneDocument;
  const child = taken.scene.objects?.[0]?.id ?? "o0";
  await postEdits(request, taken, "e2e-next", [
    { kind: "set_support", child, parent: "floor", type: "below" },
  ]);
  await page.reload();
  await expect(page.getByTestId("workflow-state")).toHaveText("in annotation");
  await expect(said).toHaveText("");
  await page.getByTestId("next-scene").click();
  await expect(page).not.toHaveURL(new RegExp(`#/scenes/${landed}$`));
  const kept = await workflowOf(request, landed);
  expect(kept.state).toBe("in_annotation");
  expect(kept.events.at(-1)?.action).toBe("claim");
  await expect(page.getByTestId("workflow-state")).toBeVisible();
  await expect(said).toHaveText(""); // nothing was given back
});
