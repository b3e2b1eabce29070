// The unsaved edits a scene page keeps in localStorage: per person, under
// holiscene.drafts/<name>/<scene> (frontend/src/state/draftStore.ts).
import type { Page } from "@playwright/test";

/** The draft this browser keeps for the scene (as stored, JSON), or "" when none. */
export async function keptDraft(page: Page, sceneId: string): Promise<string> {
  return page.evaluate(
    (id) =>
      Object.keys(localStorage)
        .filter((k) => k.startsWith("holiscene.drafts/") && k.endsWith(`/${id}`))
        .map((k) => localStorage.getItem(k) ?? "")
        .join(""),
    sceneId,
  );
}

/** Every key this browser keeps for the scene's unsaved work (drafts, set-aside, failed). */
export async function draftKeys(page: Page, sceneId: string): Promise<string[]> {
  return page.evaluate(
    (id) =>
      Object.keys(localStorage).filter((k) => k.startsWith("holiscene.draft") && k.includes(id)),
    sceneId,
  );
}
