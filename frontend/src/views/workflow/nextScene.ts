// "Next scene": take the scene to annotate next (a rejected one of yours, else the predicted
// scene the pipeline is least sure of) and open it. A button and a key: N on the scene list;
// ">" on the scene page, where N already selects the next object. A reviewer also gets "Next
// to review", which opens the scene waiting longest for review without taking anything, so
// a reviewer who means to review never becomes a scene's annotator by mistake; its key is R
// on the list and Shift+Right on the scene page (R rejects a support edge there).
import type { SceneSummary } from "@holiscene/schema";
import { ApiError } from "../../api/errors";
import { workflowApi } from "../../api/workflow";
import { button, el } from "../../dom";
import { registerShortcut } from "../../shortcuts";
import { tabStorage } from "../../state/browserStorage";
import { hasRole } from "../../state/currentUser";

/** What "Next scene" did to the scene it left, said on the page it opens (this tab only). */
const LEFT_SCENE_KEY = "holiscene.nextScene.leftScene";

/** The note about the scene left behind, once: read and forgotten. */
function takeLeftSceneNote(): string {
  const note = tabStorage()?.getItem(LEFT_SCENE_KEY) ?? "";
  tabStorage()?.removeItem(LEFT_SCENE_KEY);
  return note;
}

export interface NextSceneKeys {
  /** Take the next scene to annotate. */
  take: string;
  /** Open the next scene waiting for review (reviewers). */
  review: string;
  /** The scene open on the page: "Next to review" goes on past it through the queue. On a
   * scene page the buttons are plain: the scene's own step (Accept, Submit) is the blue one. */
  current?: string;
}

/**
 * The buttons and their message line; the keys work while they are mounted. `beforeTake`: run
 * before the next scene is taken (on a scene page: giving back the open one, untouched); what
 * it says it did is shown on the next scene's page.
 */
export function nextSceneControl(
  keys: NextSceneKeys,
  beforeTake?: () => Promise<string | null>,
): {
  element: HTMLElement;
  dispose: () => void;
} {
  const message = el("span", {
    className: "next-scene-message",
    testid: "next-scene-message",
    attrs: { role: "status" },
    text: takeLeftSceneNote(),
  });
  const reviewer = hasRole("reviewer");
  const onScenePage = keys.current !== undefined;
  const nextButton = button("Next scene", {
    className: reviewer || onScenePage ? "" : "primary",
    testid: "next-scene",
    title: onScenePage
      ? `Take the next scene to annotate: it becomes yours; this one, if you took it and ` +
        `changed nothing, goes back to the queue (${keys.take})`
      : `Take the next scene to annotate: it becomes yours (${keys.take})`,
  });
  const reviewButton = button("Next to review", {
    className: onScenePage ? "" : "primary",
    testid: "next-review",
    title: `Open the scene waiting longest for review; nothing is assigned to you (${keys.review})`,
  });
  const open = (fetch: () => Promise<SceneSummary>, failed: string) => async () => {
    nextButton.disabled = reviewButton.disabled = true;
    message.textContent = "";
    try {
      const scene = await fetch();
      window.location.hash = `#/scenes/${encodeURIComponent(scene.id)}`;
    } catch (error) {
      const why = error instanceof ApiError ? error.message : `${failed}: ${String(error)}`;
      message.textContent = [takeLeftSceneNote(), why].filter(Boolean).join(" ");
    } finally {
      nextButton.disabled = reviewButton.disabled = false;
    }
  };
  const go = open(async () => {
    const note = await beforeTake?.();
    if (note) tabStorage()?.setItem(LEFT_SCENE_KEY, note);
    return workflowApi.next();
  }, "Could not take a scene");
  nextButton.addEventListener("click", () => void go());
  const goReview = open(
    () => workflowApi.nextToReview(keys.current),
    "Could not find a scene to review",
  );
  reviewButton.addEventListener("click", () => void goReview());
  const removeTakeKey = registerShortcut({
    keys: keys.take,
    description: "Take the next scene to annotate (the most uncertain first)",
    scope: "Workflow",
    run: () => void go(),
    enabled: () => hasRole("annotator") && !nextButton.disabled,
  });
  const removeReviewKey = registerShortcut({
    keys: keys.review,
    description: "Open the next scene waiting for review (the one waiting longest)",
    scope: "Workflow",
    run: () => void goReview(),
    enabled: () => hasRole("reviewer") && !reviewButton.disabled,
    listed: () => hasRole("reviewer"),
  });
  reviewButton.hidden = !reviewer;
  const element = el("span", { className: "next-scene" }, reviewButton, nextButton, message);
  element.hidden = !hasRole("annotator");
  return {
    element,
    dispose: () => {
      removeTakeKey();
      removeReviewKey();
    },
  };
}
