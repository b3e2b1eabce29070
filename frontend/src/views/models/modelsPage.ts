// The admin page of the model registry, one kind at a time (a switch at the top): the
// Relation Network (#/models) or the object detector (#/models/detector). Every registered
// model of the kind, its training curve, the history of the active model, retraining (with
// live progress and log) and roll-back. Retraining and changing the active model are for
// admins (the server checks).
import type { Job, ModelEvent, ModelInfo } from "@holiscene/schema";
import { isFinished, pollJob } from "../../api/jobs";
import { modelsApi } from "../../api/models";
import { button, el, formatTime, hiddenErrorAlert, labelledField } from "../../dom";
import type { ModelKind } from "../../router";
import { getAuthor } from "../../state/author";
import { jobProgress } from "../common/jobProgress";

const POLL_MS = 1000;

interface KindText {
  switchLabel: string;
  title: string;
  usedBy: string;
  empty: string;
  heldoutColumn: string;
  validationColumn: string;
  retrainHint: string;
  epochs: [label: string, placeholder: string];
  synthetic: [label: string, placeholder: string];
}

const KIND_TEXT: Record<ModelKind, KindText> = {
  relation: {
    switchLabel: "Relation Network",
    title: "Relation Network models",
    usedBy:
      "The pipeline and the browser use the active model. Any model can be made active again.",
    empty: "No Relation Network model is registered yet: retrain to make one.",
    heldoutColumn: "Held-out accuracy",
    validationColumn: "Validation accuracy",
    retrainHint:
      "Trains a new Relation Network on the synthetic scenes and on every scene whose supports " +
      "a person set. A fixed fifth of those scenes is held out: the new model becomes active " +
      "only if it is at least as accurate on them as the active one. Every model is kept.",
    epochs: ["Epochs at most", "default (40)"],
    synthetic: ["Synthetic scenes", "default (1200)"],
  },
  detector: {
    switchLabel: "Object detector",
    title: "Object detector models",
    usedBy:
      "The pipeline finds objects with the active detector. Any detector can be made active again.",
    empty: "No object detector is registered yet: retrain to make one.",
    heldoutColumn: "Held-out mAP@0.5 · recall",
    validationColumn: "Validation mAP@0.5",
    retrainHint:
      "Fine-tunes a new detector on synthetic rooms and on every scene whose boxes a person " +
      "confirmed: drawn, given with the photo, accepted suggestions, or all of a scene a " +
      "reviewer accepted. A fixed fifth of those scenes is held out: the new detector becomes " +
      "active only if its mAP@0.5 on them is at least the active one's. Every detector is kept.",
    epochs: ["Epochs", "default (12)"],
    synthetic: ["Synthetic rooms", "default (300)"],
  },
};

const KINDS: ModelKind[] = ["relation", "detector"];

/** Links to each kind's page; the current one marked. */
function kindSwitch(current: ModelKind): HTMLElement {
  return el(
    "nav",
    { className: "model-kinds", testid: "model-kinds", attrs: { "aria-label": "Model kind" } },
    ...KINDS.map((kind) =>
      el("a", {
        text: KIND_TEXT[kind].switchLabel,
        testid: `model-kind-${kind}`,
        attrs: {
          href: kind === "relation" ? "#/models" : `#/models/${kind}`,
          ...(kind === current ? { "aria-current": "page" } : {}),
        },
      }),
    ),
  );
}

const STATUS_TEXT: Record<ModelInfo["status"], string> = {
  default: "committed default",
  accepted: "accepted",
  candidate: "candidate",
  rejected: "rejected",
};

const percent = (value: number | null) =>
  value === null || value < 0 ? "—" : `${(value * 100).toFixed(1)} %`;

// A detector's held-out figures are its mAP@0.5 and recall; a Relation Network's its accuracy.
const figures = (value: number, recall: number | null) =>
  recall === null ? percent(value) : `${percent(value)} · ${percent(recall)}`;

function heldoutText(model: ModelInfo): string {
  if (model.heldout_accuracy === null) return "—";
  const parent =
    model.parent_version !== null && model.parent_heldout_accuracy !== null
      ? ` (v${model.parent_version}: ${figures(model.parent_heldout_accuracy, model.parent_heldout_recall)})`
      : "";
  return `${figures(model.heldout_accuracy, model.heldout_recall)}${parent}`;
}

function numberField(label: string, name: string, placeholder: string, max: number) {
  const input = el("input", {
    testid: `retrain-${name}`,
    attrs: { type: "number", name, min: name === "epochs" ? 1 : 0, max, step: 1, placeholder },
  });
  const field = labelledField(label, input);
  return { input, field };
}

const readNumber = (input: HTMLInputElement) =>
  input.value.trim() === "" ? null : Math.round(Number(input.value));

export function mountModelsPage(container: HTMLElement, kind: ModelKind = "relation"): () => void {
  const abort = new AbortController();
  const text = KIND_TEXT[kind];
  const epochs = numberField(text.epochs[0], "epochs", text.epochs[1], 500);
  const synthetic = numberField(text.synthetic[0], "synthetic", text.synthetic[1], 20000);
  const retrain = button("Retrain", {
    className: "primary",
    testid: "retrain-button",
    type: "submit",
  });
  const retrainError = hiddenErrorAlert("retrain-error");
  const progress = jobProgress("retrain-progress");
  progress.element.hidden = true;
  const log = el("pre", { className: "job-log", testid: "retrain-log", attrs: { hidden: true } });
  const form = el(
    "form",
    { className: "card", testid: "retrain-form" },
    el("h2", { text: "Retrain" }),
    el("p", { className: "field-hint", text: text.retrainHint }),
    el("div", { className: "field-grid" }, epochs.field, synthetic.field),
    el("div", { className: "form-actions" }, retrain),
    retrainError,
    progress.element,
    log,
  );

  const status = el("p", { className: "list-status", testid: "model-list-status" });
  const notice = el("p", {
    className: "list-status",
    testid: "model-notice",
    attrs: { role: "status", "aria-live": "polite" },
  });
  const body = el("tbody");
  const table = el(
    "table",
    { className: "scene-table model-table", testid: "model-list" },
    el(
      "thead",
      {},
      el(
        "tr",
        {},
        ...[
          "Version",
          "Created",
          "Status",
          text.heldoutColumn,
          text.validationColumn,
          "Labelled scenes",
          "",
          "",
        ].map((text) => el("th", { text, attrs: { scope: "col" } })),
      ),
    ),
    body,
  );
  const curveTitle = el("h2", { text: "Training curve" });
  const curveImage = el("img", {
    className: "curve-image",
    testid: "model-curve",
    attrs: { alt: "", width: 600, height: 350 },
  });
  const curveEmpty = el("p", { className: "field-hint", text: "This model has no curve." });
  const curveCard = el("section", { className: "card" }, curveTitle, curveImage, curveEmpty);
  const history = el("ol", { className: "model-history", testid: "model-history" });

  let models: ModelInfo[] = [];
  let shownCurve: string | null = null;

  const showCurve = (model: ModelInfo | undefined) => {
    curveCard.hidden = !model;
    if (!model) return;
    shownCurve = model.id;
    curveTitle.textContent = `Training curve of v${model.version}`;
    curveImage.hidden = !model.has_curve;
    curveEmpty.hidden = model.has_curve;
    if (model.has_curve) {
      curveImage.src = modelsApi.curveUrl(model.id);
      curveImage.alt = `Training loss and validation accuracy of model v${model.version}`;
    }
  };

  const promote = async (model: ModelInfo, button: HTMLButtonElement) => {
    button.disabled = true;
    notice.textContent = `Making v${model.version} active…`;
    try {
      await modelsApi.promote(model.id, { author: getAuthor(), note: null });
      notice.textContent = `v${model.version} is now the active model.`;
      await refresh();
    } catch (error) {
      button.disabled = false;
      notice.textContent = `Could not make v${model.version} active: ${String(error)}`;
    }
  };

  const modelRow = (model: ModelInfo): HTMLTableRowElement => {
    const action = model.active
      ? el("span", { className: "badge badge--active", text: "Active" })
      : button("Make active", {
          testid: `promote-${model.version}`,
          onClick: (event) => void promote(model, event.currentTarget as HTMLButtonElement),
        });
    const curve = button("Curve", {
      testid: `curve-${model.version}`,
      disabled: !model.has_curve,
      onClick: () => showCurve(model),
    });
    return el(
      "tr",
      {
        testid: `model-row-${model.version}`,
        className: model.active ? "is-active" : "",
        attrs: { "data-status": model.status },
      },
      el("th", { text: `v${model.version}`, attrs: { scope: "row", title: model.id } }),
      el("td", { text: formatTime(model.created_at) }),
      el(
        "td",
        { attrs: { title: model.note ?? "" } },
        el("span", {
          className: `badge badge--${model.status}`,
          text: STATUS_TEXT[model.status],
        }),
      ),
      el("td", { text: heldoutText(model) }),
      el("td", { text: percent(model.validation_accuracy) }),
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

  const eventItem = (event: ModelEvent): HTMLLIElement => {
    const what =
      event.action === "seed"
        ? `v${event.model_version} registered as the first model`
        : `${event.action === "rollback" ? "rolled back" : "promoted"} to v${event.model_version}` +
          (event.previous_version !== null ? ` (from v${event.previous_version})` : "");
    return el(
      "li",
      {},
      el("strong", { text: what }),
      ` by ${event.actor} · ${formatTime(event.at)}`,
      event.note ? ` · ${event.note}` : "",
    );
  };

  async function refresh(): Promise<void> {
    try {
      const [listed, events] = await Promise.all([
        modelsApi.listModels(abort.signal, kind),
        modelsApi.listEvents(abort.signal, kind),
      ]);
      models = listed;
      body.replaceChildren(...models.map(modelRow));
      table.hidden = models.length === 0;
      status.textContent = models.length === 0 ? text.empty : "";
      history.replaceChildren(...events.map(eventItem));
      const shown = models.find((m) => m.id === shownCurve) ?? models.find((m) => m.active);
      showCurve(shown ?? models[0]);
    } catch (error) {
      if (!abort.signal.aborted) status.textContent = `Could not load the models: ${String(error)}`;
    }
  }

  const showJob = (job: Job) => {
    progress.element.hidden = false;
    progress.update(job);
    log.hidden = job.log === "";
    const atBottom = log.scrollTop + log.clientHeight >= log.scrollHeight - 4;
    log.textContent = job.log;
    if (atBottom) log.scrollTop = log.scrollHeight;
    retrain.disabled = !isFinished(job);
  };

  const follow = async (job: Job) => {
    try {
      const final = await pollJob(job, {
        onUpdate: showJob,
        signal: abort.signal,
        intervalMs: POLL_MS,
      });
      showJob(final);
      await refresh();
    } catch (error) {
      if (!abort.signal.aborted) {
        retrain.disabled = false;
        retrainError.hidden = false;
        retrainError.textContent = `Lost track of the retrain job: ${String(error)}`;
      }
    }
  };

  form.addEventListener("submit", async (event) => {
    event.preventDefault();
    retrain.disabled = true;
    retrainError.hidden = true;
    try {
      const job = await modelsApi.startRetrain(
        {
          author: getAuthor(),
          max_epochs: readNumber(epochs.input),
          synthetic_scenes: readNumber(synthetic.input),
        },
        kind,
      );
      void follow(job);
    } catch (error) {
      retrain.disabled = false;
      retrainError.hidden = false;
      retrainError.textContent = `Retraining did not start: ${String(error instanceof Error ? error.message : error)}`;
    }
  });

  container.replaceChildren(
    el(
      "div",
      {
        className: "list-page models-page",
        testid: "models-page",
        attrs: { "data-kind": kind },
      },
      el(
        "p",
        { className: "breadcrumb" },
        el("a", { text: "← All scenes", attrs: { href: "#/" } }),
      ),
      kindSwitch(kind),
      el(
        "section",
        { className: "card" },
        el("h2", { text: text.title }),
        el("p", { className: "field-hint", text: text.usedBy }),
        status,
        notice,
        el("div", { className: "table-scroll" }, table),
      ),
      curveCard,
      form,
      el("section", { className: "card" }, el("h2", { text: "History" }), history),
    ),
  );

  void refresh();
  void modelsApi
    .latestRetrainJob(abort.signal, kind)
    .then((job) => {
      if (!job) return;
      if (isFinished(job)) showJob(job);
      else void follow(job);
    })
    .catch(() => {
      // The list shows any load error; the last job is only a convenience.
    });

  return () => abort.abort();
}
