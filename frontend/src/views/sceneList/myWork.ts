// The list's "Mine to do": the scenes a person annotates now, those a reviewer sent back to them
// first (someone waits on those), each group in the list's own order.
import type { SceneSummary } from "@holiscene/schema";

/** The state filter's value for this view (not a scene state). */
export const MINE = "mine";

export function myWork(scenes: readonly SceneSummary[], me: string | null): SceneSummary[] {
  if (me === null) return [];
  const held = scenes.filter(
    (s) => s.assignee === me && (s.state === "in_annotation" || s.state === "rejected"),
  );
  return [...sentBack(held, me), ...held.filter((s) => s.state !== "rejected")];
}

/** The scenes a reviewer sent back to `me` to fix: the list says so above every filter. */
export function sentBack(scenes: readonly SceneSummary[], me: string | null): SceneSummary[] {
  return me === null ? [] : scenes.filter((s) => s.assignee === me && s.state === "rejected");
}

/** "2 scenes were sent back to you: a, b." (names cut after a few). */
export function sentBackText(scenes: readonly SceneSummary[]): string {
  const names = scenes.slice(0, 3).map((s) => s.name);
  const more = scenes.length > 3 ? ` and ${scenes.length - 3} more` : "";
  const count = scenes.length === 1 ? "1 scene was" : `${scenes.length} scenes were`;
  return `${count} sent back to you by a reviewer: ${names.join(", ")}${more}.`;
}
