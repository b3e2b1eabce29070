// The scene page's Archive / Restore button (admins): a scene nobody should work on (a junk
// photo, a duplicate) leaves the lists, "Next scene", reviews and retraining and turns read
// only, every revision kept; Restore brings it back as it was.
import type { SceneSummary } from "@holiscene/schema";
import { workflowApi } from "../../api/workflow";
import { button } from "../../dom";
import { hasRole } from "../../state/currentUser";

export interface ArchiveControl {
  element: HTMLButtonElement;
  /** Show the button for the scene as the list has it (hidden for others than admins). */
  show(summary: SceneSummary | null): void;
}

/** `changed` runs after the scene was archived or restored (the page reloads it). */
export function archiveControl(
  sceneId: string,
  changed: () => void,
  fail: (error: unknown) => void,
): ArchiveControl {
  const element = button("Archive", { testid: "archive-scene", hidden: true });
  let current: SceneSummary | null = null;
  element.addEventListener("click", async () => {
    const scene = current;
    if (!scene) return;
    const archived = scene.archived_at != null;
    if (
      !archived &&
      !window.confirm(
        `Archive "${scene.name}"? It leaves the scene list, "Next scene", reviews, retraining ` +
          "and batch runs, and becomes read only. Every revision is kept, and an admin can " +
          "restore it (the list's Archived filter shows it).",
      )
    )
      return;
    element.disabled = true;
    try {
      await (archived ? workflowApi.unarchive(sceneId) : workflowApi.archive(sceneId));
      changed();
    } catch (error) {
      fail(error);
    } finally {
      element.disabled = false;
    }
  });
  return {
    element,
    show(summary) {
      current = summary;
      element.hidden = summary === null || !hasRole("admin");
      const archived = summary?.archived_at != null;
      element.textContent = archived ? "Restore" : "Archive";
      element.title = archived
        ? `Archived by ${summary?.archived_by ?? "an admin"}: bring it back to the lists, as it was`
        : "Take this scene out of the lists and 'Next scene' (a junk photo, a duplicate); read " +
          "only, every revision kept";
    },
  };
}
