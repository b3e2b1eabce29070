// A model's figures as the models page writes them: in its table and in the question asked
// before it is made active (the admin decides on the numbers, side by side with the active
// model's, and sees how few scenes a held-out figure may rest on).
import { type ModelInfo, RETRAINING, type RetrainReadiness } from "@holiscene/schema";
import type { KindText } from "./kindText";

export const percent = (value: number | null) =>
  value === null || value < 0 ? "—" : `${(value * 100).toFixed(1)}%`;

// A detector's held-out figures are its mAP@0.5 and recall; a Relation Network's its accuracy.
const figures = (value: number, recall: number | null) =>
  recall === null ? percent(value) : `${percent(value)} · ${percent(recall)}`;

/** `model`'s figures on another model's held-out scenes, and whose. */
interface Comparison {
  by: ModelInfo;
  accuracy: number;
  recall: number | null;
}

/** `model`'s newest figures on a later model's held-out scenes: as the parent it was
 * compared with, or as another registered model its retrain measured too; undefined when no
 * retrain measured it. */
function newestComparison(model: ModelInfo, others: readonly ModelInfo[]): Comparison | undefined {
  return others
    .flatMap((m): Comparison[] => {
      if (m.parent_id === model.id && m.parent_heldout_accuracy !== null)
        return [{ by: m, accuracy: m.parent_heldout_accuracy, recall: m.parent_heldout_recall }];
      const measured = (m.heldout_others ?? []).find((f) => f.model_id === model.id);
      return measured
        ? [{ by: m, accuracy: measured.accuracy, recall: measured.recall ?? null }]
        : [];
    })
    .sort((a, b) => b.by.version - a.by.version)[0];
}

/** The held-out figures, the parent's beside them, and how many items they rest on (a
 * figure from a handful of objects decides little, and the admin should see that). A model
 * never judged on held-out scenes of its own (a shipped one) gives its figure from the newest
 * retrain that measured it (as the parent, or as another registered model), on that retrain's
 * held-out scenes. */
export function heldoutText(
  model: ModelInfo,
  text: KindText,
  others: readonly ModelInfo[] = [],
): string {
  if (model.heldout_accuracy === null) {
    const seen = newestComparison(model, others);
    if (!seen) return "—";
    const items = seen.by.heldout_items;
    const [one, many] = text.heldoutItems;
    const count = items == null ? "" : ` (${items} ${items === 1 ? one : many})`;
    return `${figures(seen.accuracy, seen.recall)} on v${seen.by.version}'s held-out scenes${count}`;
  }
  const parent =
    model.parent_version !== null && model.parent_heldout_accuracy !== null
      ? ` (v${model.parent_version}: ${figures(model.parent_heldout_accuracy, model.parent_heldout_recall)})`
      : "";
  const items = model.heldout_items;
  const [one, many] = text.heldoutItems;
  const count = items == null ? "" : `, on ${items} ${items === 1 ? one : many}`;
  return `${figures(model.heldout_accuracy, model.heldout_recall)}${parent}${count}`;
}

/** A model's status as the list and the curve's title say it. */
export const STATUS_TEXT: Record<ModelInfo["status"], string> = {
  default: "shipped with the app",
  accepted: "accepted",
  candidate: "candidate",
  rejected: "rejected",
};

/** A column's title inside a sentence: its first letter small, the rest as written (mAP). */
const inSentence = (title: string) => title.charAt(0).toLowerCase() + title.slice(1);

/** One model's figures on one line: "held-out … (N scenes); validation …". */
function figuresLine(model: ModelInfo, text: KindText, others: readonly ModelInfo[]): string {
  const scenes = model.heldout_scenes;
  const from = scenes > 0 ? ` (${scenes} held-out ${scenes === 1 ? "scene" : "scenes"})` : "";
  return (
    `${inSentence(text.heldoutColumn)} ${heldoutText(model, text, others)}${from}; ` +
    `${inSentence(text.validationColumn)} ${percent(model.validation_accuracy)}`
  );
}

/** What "Make active" asks: the model's figures beside the active model's. */
export function promoteQuestion(
  model: ModelInfo,
  active: ModelInfo | undefined,
  text: KindText,
  others: readonly ModelInfo[] = [],
): string {
  const lost =
    model.status === "rejected"
      ? `v${model.version} did worse than the model it was compared with on the held-out scenes. `
      : "";
  const lines = [
    `${lost}${cautions(model, active, others).join("")}` +
      `Make v${model.version} the active model? Pipeline runs and suggestions use it from now on.`,
    "",
    `v${model.version}: ${figuresLine(model, text, others)}`,
  ];
  if (active && active.id !== model.id)
    lines.push(`v${active.version} (active now): ${figuresLine(active, text, others)}`);
  return lines.join("\n");
}

/** Held-out figures on fewer items than this decide little (one item is a whole share). */
export const FEW_HELDOUT_ITEMS = RETRAINING.few_heldout_items;
/** A validation figure this much below the active model's is a warning of its own. */
export const WORSE_VALIDATION = 0.05;

/** Warnings before making `model` active: much worse on validation than the active model,
 * or a held-out figure that rests on a handful of items. */
function cautions(
  model: ModelInfo,
  active: ModelInfo | undefined,
  others: readonly ModelInfo[],
): string[] {
  const out: string[] = [];
  const mine = model.validation_accuracy;
  const theirs = active && active.id !== model.id ? active.validation_accuracy : null;
  if (mine !== null && theirs !== null && theirs - mine >= WORSE_VALIDATION) {
    const points = ((theirs - mine) * 100).toFixed(1);
    out.push(
      `Warning: its validation figure is ${points} points below the active model's ` +
        "(each measured on its own training run's validation scenes, not the same ones).",
    );
  }
  // Nothing held out judged it (a model shipped with the app, never compared with a model
  // retrained from it): its figures come from elsewhere, not from this team's photos.
  const judged = (m: ModelInfo) =>
    m.heldout_accuracy !== null || newestComparison(m, others) !== undefined;
  if (!judged(model) && active && active.id !== model.id) {
    out.push(
      judged(active)
        ? `Warning: v${model.version} was never measured on held-out scenes of this team's ` +
            "labels; its figures below are not from the same scenes as the active model's."
        : `Warning: neither v${model.version} nor the active v${active.version} was measured ` +
            "on held-out scenes of this team's labels: the figures below do not say which " +
            "does better on them.",
    );
  }
  const items = model.heldout_items;
  if (model.heldout_accuracy !== null && items != null && items < FEW_HELDOUT_ITEMS) {
    out.push(
      `Its held-out figure rests on ${items} ${items === 1 ? "item" : "items"} only: ` +
        "too few to tell two models apart.",
    );
  }
  return out.map((line) => `${line} `);
}

/** "3 labelled scenes (scenes with ...): enough" / "1 of the 2 needed" */
export function readinessText(readiness: RetrainReadiness): string {
  const counted = labelledText(readiness);
  // One retrain runs at a time (it takes the whole machine): say which one this waits for.
  return readiness.other_retrain
    ? `${counted} Waiting: ${readiness.other_retrain} is running, and one retrain runs at a time.`
    : counted;
}

function labelledText(readiness: RetrainReadiness): string {
  const { labelled_scenes: count, heldout_scenes: heldout, needed, what } = readiness;
  const scenes = `${count} labelled ${count === 1 ? "scene" : "scenes"} (${what})`;
  if (count < needed) {
    return `${scenes}: at least ${needed} are needed, one to learn from and one to judge by.`;
  }
  // Scenes of one photo share a side of the held-out split: all of one photo, none is.
  if (heldout === 0) {
    return `${scenes}: all of one photo, and a model is never judged on a photo it learned from; label a scene of another photo.`;
  }
  // The held-out share is a fifth only with many scenes: with few, one is held out.
  const held = heldout === 1 ? "1 of them is" : `${heldout} of them are`;
  return `${scenes}: ${held} held out to judge the new model, never trained on.`;
}
