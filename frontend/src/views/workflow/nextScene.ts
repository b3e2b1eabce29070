// "Next scene": take the scene to annotate next (a rejected one of yours, else the predicted
// scene the pipeline is least sure of) and open it. A button and a key: N on the scene list;
// ">" on the scene page, where N already selects the next object.
import { ApiError } from "../../api/errors";
import { workflowApi } from "../../api/workflow";
import { button, el } from "../../dom";
import { registerShortcut } from "../../shortcuts";
import { hasRole } from "../../state/currentUser";

/** The button and its message line; `key` works while they are mounted. */
export function nextSceneControl(key: string): { element: HTMLElement; dispose: () => void } {
  const message = el("span", {
    className: "next-scene-message",
    testid: "next-scene-message",
    attrs: { role: "status" },
  });
  const nextButton = button("Next scene", {
    className: "primary",
    testid: "next-scene",
    title: `Take the next scene to annotate (${key})`,
  });
  const go = async () => {
    nextButton.disabled = true;
    message.textContent = "";
    try {
      const scene = await workflowApi.next();
      window.location.hash = `#/scenes/${encodeURIComponent(scene.id)}`;
    } catch (error) {
      message.textContent =
        error instanceof ApiError ? error.message : `Could not take a scene: ${String(error)}`;
    } finally {
      nextButton.disabled = false;
    }
  };
  nextButton.addEventListener("click", () => void go());
  const removeKey = registerShortcut({
    keys: key,
    description: "Take the next scene to annotate (the most uncertain first)",
    scope: "Workflow",
    run: () => void go(),
    enabled: () => hasRole("annotator") && !nextButton.disabled,
  });
  const element = el("span", { className: "next-scene" }, nextButton, message);
  element.hidden = !hasRole("annotator");
  return { element, dispose: removeKey };
}
