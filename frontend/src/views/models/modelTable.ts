// The models page's list: every registered model of the kind, its figures, its curve button
// and "Make active" (a promotion, or a roll-back to an older model).
import type { ModelInfo } from "@holiscene/schema";
import { modelsApi } from "../../api/models";
import { button, el, formatTime } from "../../dom";
import { getAuthor } from "../../state/author";
import { hasRole } from "../../state/currentUser";
import type { KindText } from "./kindText";
import { heldoutText, percent, promoteQuestion, STATUS_TEXT } from "./modelFigures";

export interface ModelTableInputs {
  text: KindText;
  /** "Curve" was pressed on a model's row. */
  onCurve(model: ModelInfo): void;
  /** `model` was made active: the page loads the list again. */
  onPromoted(model: ModelInfo): Promise<void>;
}

export interface ModelTable {
  /** The card with the title, status lines and the table. */
  element: HTMLElement;
  show(models: ModelInfo[]): void;
  /** Say the list could not be loaded. */
  showError(message: string): void;
}

export function modelTable({ text, onCurve, onPromoted }: ModelTableInputs): ModelTable {
  const status = el("p", { className: "list-status", testid: "model-list-status" });
  const notice = el("p", {
    className: "list-status",
    testid: "model-notice",
    attrs: { role: "status", "aria-live": "polite" },
  });
  const body = el("tbody");
  let shown: ModelInfo[] = [];
  const columns = [
    "Version",
    "Created",
    "Status",
    text.heldoutColumn,
    text.validationColumn,
    "Labelled scenes",
    "",
    "",
  ];
  const table = el(
    "table",
    { className: "scene-table model-table", testid: "model-list" },
    el(
      "thead",
      {},
      el("tr", {}, ...columns.map((name) => el("th", { text: name, attrs: { scope: "col" } }))),
    ),
    body,
  );

  const promote = async (model: ModelInfo, promoteButton: HTMLButtonElement) => {
    // Every pipeline run and the page's suggestions change with the active model: asked first.
    const active = shown.find((m) => m.active);
    if (!window.confirm(promoteQuestion(model, active, text, shown))) return;
    promoteButton.disabled = true;
    notice.textContent = `Making v${model.version} active…`;
    try {
      await modelsApi.promote(model.id, { author: getAuthor(), note: null });
      notice.textContent = `v${model.version} is now the active model.`;
      await onPromoted(model);
    } catch (error) {
      promoteButton.disabled = false;
      const reason = error instanceof Error ? error.message : String(error);
      notice.textContent = `Could not make v${model.version} active: ${reason}`;
    }
  };

  const modelRow = (model: ModelInfo): HTMLTableRowElement => {
    const action = model.active
      ? el("span", { className: "badge badge--active", text: "Active" })
      : hasRole("admin")
        ? button("Make active", {
            testid: `promote-${model.version}`,
            onClick: (event) => void promote(model, event.currentTarget as HTMLButtonElement),
          })
        : el("span");
    const curve = button("Curve", {
      testid: `curve-${model.version}`,
      disabled: !model.has_curve,
      // A greyed button should say why: shipped and converted models were not trained here.
      title: model.has_curve ? undefined : "No training curve: this model was not trained here",
      onClick: () => onCurve(model),
    });
    return el(
      "tr",
      {
        testid: `model-row-${model.version}`,
        className: model.active ? "is-active" : "",
        attrs: { "data-status": model.status },
      },
      // Which network it is: three shipped detectors would otherwise be three bare versions.
      el(
        "th",
        { attrs: { scope: "row", title: model.id } },
        `v${model.version}`,
        model.name ? el("span", { className: "model-name", text: model.name }) : "",
      ),
      el("td", { text: formatTime(model.created_at) }),
      el(
        "td",
        { attrs: { title: model.note ?? "" } },
        el("span", {
          className: `badge badge--${model.status}`,
          // A model an admin made active although it lost (or tied) its held-out test says so.
          text:
            model.active && (model.status === "rejected" || model.status === "candidate")
              ? `${STATUS_TEXT[model.status]}, made active by hand`
              : STATUS_TEXT[model.status],
        }),
      ),
      el("td", {
        text: heldoutText(model, text, shown),
        // A model never judged on held-out scenes of its own has figures only from the
        // comparisons with models retrained from it: say so.
        attrs: {
          title:
            model.heldout_accuracy === null
              ? "Not measured on held-out scenes when it was registered; a model retrained " +
                "from it was compared with it on that model's held-out scenes"
              : undefined,
        },
      }),
      el("td", {
        text: percent(model.validation_accuracy),
        attrs: { title: model.validation_accuracy === null ? text.noValidation : undefined },
      }),
      el("td", {
        text:
          model.training_scenes + model.heldout_scenes > 0
            ? `${model.training_scenes} trained, ${model.heldout_scenes} held out`
            : "—",
      }),
      el("td", {}, curve),
      el("td", {}, action),
    );
  };

  const element = el(
    "section",
    { className: "card" },
    el("h2", { text: text.title }),
    el("p", { className: "field-hint", text: text.usedBy }),
    status,
    notice,
    el("div", { className: "table-scroll" }, table),
  );
  return {
    element,
    show(models) {
      shown = models;
      body.replaceChildren(...models.map(modelRow));
      table.hidden = models.length === 0;
      status.textContent = models.length === 0 ? text.empty : "";
    },
    showError(message) {
      status.textContent = message;
    },
  };
}
