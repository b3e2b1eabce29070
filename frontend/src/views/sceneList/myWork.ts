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
  return [
    ...held.filter((s) => s.state === "rejected"),
    ...held.filter((s) => s.state !== "rejected"),
  ];
}
