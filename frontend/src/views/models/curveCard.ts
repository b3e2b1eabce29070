// The models page's training curve card: the curve of one model (the active one, or the one
// whose "Curve" button was pressed last).
import type { ModelInfo } from "@holiscene/schema";
import { modelsApi } from "../../api/models";
import { el } from "../../dom";
import { STATUS_TEXT } from "./modelFigures";

export interface CurveCard {
  element: HTMLElement;
  /** The model whose curve is shown, if any. */
  readonly shownId: string | null;
  /** Show the model's curve; nothing hides the card. */
  show(model: ModelInfo | undefined): void;
  /** Whether a retrain runs: its curve comes when it ends, and the card says so meanwhile. */
  retrainRunning(running: boolean): void;
}

export function curveCard(): CurveCard {
  const title = el("h2", { text: "Training curve" });
  const image = el("img", {
    className: "curve-image",
    testid: "model-curve",
    attrs: { alt: "", width: 600, height: 350 },
  });
  const empty = el("p", { className: "field-hint", text: "This model has no curve." });
  const waiting = el("p", {
    className: "field-hint",
    testid: "curve-waiting",
    text: "A retrain is running: its curve shows here when it ends; its log is under Retrain.",
  });
  waiting.hidden = true;
  const element = el("section", { className: "card" }, title, waiting, image, empty);
  let shownId: string | null = null;
  return {
    element,
    get shownId() {
      return shownId;
    },
    retrainRunning(running) {
      waiting.hidden = !running;
    },
    show(model) {
      element.hidden = !model;
      if (!model) return;
      shownId = model.id;
      // Its standing too: the curve shown may be of a candidate or a rejected model.
      const standing = model.active ? "active" : STATUS_TEXT[model.status];
      title.textContent = `Training curve of v${model.version} (${standing})`;
      image.hidden = !model.has_curve;
      empty.hidden = model.has_curve;
      if (model.has_curve) {
        image.src = modelsApi.curveUrl(model.id);
        image.alt = `Training loss and validation accuracy of model v${model.version}`;
      }
    },
  };
}
