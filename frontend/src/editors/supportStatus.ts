// The status chip of an object's row in the support list: where its stored support comes
// from (the pipeline's guess and how sure, a person's label, an unsaved change) and, when
// the menus beside it show the model's live suggestion instead, what is stored (what a
// reviewer sees and a submit sends), so that the row never shows only the suggestion.
import type { StageRun } from "@holiscene/schema";
import { percentText } from "../dom";
import type { ShownSupport } from "../state/supportGraph";

export interface SupportStatus {
  text: string;
  title: string;
}

/** The chip for `support` (undefined: none); `suggested`: the menus show the model's
 * suggestion, not `support`; `stages`: the scene's pipeline runs (which model guessed). */
export function supportStatus(
  support: ShownSupport | undefined,
  suggested: boolean,
  stages: readonly StageRun[],
): SupportStatus {
  const source = sourceTitle(support, supportModel(stages));
  if (!suggested) return { text: statusText(support), title: source };
  const stored = support ? `${support.parent} · ${support.type}` : "no supporter";
  return {
    text: support ? `stored: ${support.parent}` : "none stored",
    title: `Stored: ${stored}; the menus show the model's suggestion instead (A accepts it). ${source}`,
  };
}

function statusText(support: ShownSupport | undefined): string {
  if (!support) return "no supporter";
  if (support.pending) return "unsaved";
  if (support.source === "manual") return `manual${support.author ? ` · ${support.author}` : ""}`;
  const confidence = support.confidence;
  return typeof confidence === "number" ? `auto · ${percentText(confidence)}` : "auto";
}

/** The model whose guesses the stored supports are, as the pipeline run recorded it
 * ("Relation Network v2"; null: run outside a server, or before models were recorded). */
function supportModel(stages: readonly StageRun[]): string | null {
  return stages.find((run) => run.model && run.name.startsWith("supports_from_"))?.model ?? null;
}

/** What the stored support stands for; `guessedBy`: the model of the guesses. */
function sourceTitle(support: ShownSupport | undefined, guessedBy: string | null): string {
  if (!support) return "No supporter yet: pick one in the menu, or drag the arrow on the photo";
  if (support.pending) return "Changed here, not saved yet";
  if (support.source === "manual")
    return `Set by ${support.author ?? "a person"}: a label, which retraining learns from`;
  const sure =
    typeof support.confidence === "number" ? `, ${percentText(support.confidence)} sure` : "";
  const by = guessedBy ? ` by the ${guessedBy}` : "";
  return `The pipeline's guess${by}${sure}; nobody has checked it yet`;
}
