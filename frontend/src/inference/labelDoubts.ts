// People's support labels the Relation Network is sure are something else. A reviewer checks
// these first: a label that contradicts a confident model is more often a slip (a nightstand
// hung from the ceiling) than a discovery. The model is not the judge, so these are flagged,
// never changed.
import type { ShownSupport } from "../state/supportGraph";
import type { SceneScores, SupportSuggestion } from "./supportModel";

/** How sure the model's best answer must be before a person's other label is flagged. */
export const DOUBT_PROBABILITY = 0.8;

/** Child id -> the model's answer, for each person's label (saved or not) that differs from
 * an answer the model gives at least DOUBT_PROBABILITY. */
export function doubtedLabels(
  shown: ReadonlyMap<string, ShownSupport>,
  scores: SceneScores | null,
): Map<string, SupportSuggestion> {
  const doubted = new Map<string, SupportSuggestion>();
  for (const { id, ranked } of scores?.ranked ?? []) {
    const label = shown.get(id);
    const best = ranked[0];
    if (label?.source !== "manual" || !best) continue;
    if (best.probability < DOUBT_PROBABILITY) continue;
    if (best.supporter !== label.parent || best.type !== label.type) doubted.set(id, best);
  }
  return doubted;
}
