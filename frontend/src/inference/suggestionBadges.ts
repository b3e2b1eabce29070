// The model's answer beside each object in the support editor's table: a badge with the most
// probable supporter and type, the next answers in its tooltip. Where a person's label
// contradicts a confident answer (labelDoubts.ts) the badge turns orange and says so.
import { STRUCTURAL_SUPPORT_TYPES } from "@holiscene/schema";
import { el, percentText } from "../dom";
import type { SceneScores, SupportSuggestion } from "./supportModel";

const answer = (s: SupportSuggestion) => `${s.supporter} · ${s.type} ${percentText(s.probability)}`;

/** The badge's short answer: the type only where it says something ("o5 · behind"); "below"
 * is how an object rests on another, and the room's parts hold things up one way only. The
 * row then keeps the badge beside the support's status (the list shows more objects). */
const shortAnswer = (s: SupportSuggestion) =>
  s.type === "below" || s.supporter in STRUCTURAL_SUPPORT_TYPES
    ? `${s.supporter} ${percentText(s.probability)}`
    : answer(s);

/** Put the badges into `table`'s object rows (`tr[data-object]`), unless they are there
 * already with the same doubts. */
export function showSuggestionBadges(
  table: HTMLElement,
  scores: SceneScores | null,
  doubted: ReadonlyMap<string, SupportSuggestion> = new Map(),
): void {
  const ranked = scores?.ranked ?? [];
  const shown = table.querySelectorAll(".badge--suggestion");
  const doubts = [...doubted.keys()].sort().join(" ");
  const same = shown.length === ranked.length && [...shown].every((b) => b.isConnected);
  if (same && table.dataset.doubted === doubts) return;
  table.dataset.doubted = doubts;
  for (const badge of shown) badge.remove();
  for (const s of ranked) {
    const best = s.ranked[0];
    const cell = table.querySelector(`tr[data-object="${CSS.escape(s.id)}"] th`);
    if (!best || !cell) continue;
    const doubt = doubted.has(s.id);
    const alternatives = s.ranked.slice(0, 3).map(answer).join("\n");
    cell.append(
      el("span", {
        className: doubt ? "badge badge--suggestion badge--doubt" : "badge badge--suggestion",
        testid: `support-suggestion-${s.id}`,
        text: `model: ${shortAnswer(best)}`,
        attrs: {
          "data-supporter": best.supporter,
          "data-type": best.type,
          title: doubt
            ? `The model is ${percentText(best.probability)} sure of ${best.supporter} · ` +
              `${best.type}, not the label set by a person: check it.\n${alternatives}`
            : // The live suggestions decode the whole scene at once: they may differ from
              // this object's own best answer.
              `The support network's answers for this object alone:\n${alternatives}\n` +
              "Live suggestions weigh them with the class priors and what the other objects " +
              "rest on, so they can differ.",
        },
      }),
    );
  }
}
