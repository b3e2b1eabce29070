// The model's answer beside each object in the support editor's table: a badge with the most
// probable supporter and type, the next answers in its tooltip.
import { el } from "../dom";
import type { SceneScores, SupportSuggestion } from "./supportModel";

const percent = (p: number) => `${Math.round(p * 100)}%`;
const answer = (s: SupportSuggestion) => `${s.supporter} · ${s.type} ${percent(s.probability)}`;

/** Put the badges into `table`'s object rows (`tr[data-object]`), unless they are there. */
export function showSuggestionBadges(table: HTMLElement, scores: SceneScores | null): void {
  const ranked = scores?.ranked ?? [];
  const shown = table.querySelectorAll(".badge--suggestion");
  if (shown.length === ranked.length && [...shown].every((b) => b.isConnected)) return;
  for (const badge of shown) badge.remove();
  for (const s of ranked) {
    const best = s.ranked[0];
    const cell = table.querySelector(`tr[data-object="${CSS.escape(s.id)}"] th`);
    if (!best || !cell) continue;
    cell.append(
      el("span", {
        className: "badge badge--suggestion",
        testid: `support-suggestion-${s.id}`,
        text: `model: ${answer(best)}`,
        attrs: { title: s.ranked.slice(0, 3).map(answer).join("\n") },
      }),
    );
  }
}
