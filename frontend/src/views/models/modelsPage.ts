// The admin page of the model registry, one kind at a time (a switch at the top): the
// Relation Network (#/models) or the object detector (#/models/detector). Every registered
// model of the kind, its training curve, the history of the active model, retraining (with
// live progress and log) and roll-back. Retraining and changing the active model are for
// admins (the server checks).
import { sleep } from "../../api/jobs";
import { modelsApi } from "../../api/models";
import { el } from "../../dom";
import type { ModelKind } from "../../router";
import { hasRole } from "../../state/currentUser";
import { curveCard } from "./curveCard";
import { KIND_TEXT } from "./kindText";
import { modelHistory } from "./modelHistory";
import { modelTable } from "./modelTable";
import { retrainForm } from "./retrainForm";

// One panel per file: the list (modelTable), the training curve (curveCard), retraining
// (retrainForm) and the history (modelHistory); this page lays them out and loads them.

const KINDS: ModelKind[] = ["relation", "detector"];
const OTHER_RETRAIN_POLL_MS = 3000;

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

export function mountModelsPage(container: HTMLElement, kind: ModelKind = "relation"): () => void {
  const abort = new AbortController();
  const text = KIND_TEXT[kind];
  const curve = curveCard();
  const history = modelHistory();
  // A finished retrain shows the new model's curve: it is what the admin waited for.
  // A retrain that registered a model shows its curve; one cancelled or failed leaves the
  // curve the admin was reading.
  const form = retrainForm({
    kind,
    text,
    signal: abort.signal,
    onFinished: (job) => refresh(job.status === "succeeded"),
    onJob: (job) => curve.retrainRunning(job.status === "queued" || job.status === "running"),
  });
  const table = modelTable({
    text,
    onCurve: curve.show,
    onPromoted: (model) => {
      form.activeChanged();
      // The curve of the model just made active (the admin's next question is what it is).
      curve.show(model);
      return refresh();
    },
  });
  const admin = hasRole("admin");
  form.element.hidden = !admin;
  const adminsOnly = el("p", {
    className: "field-hint",
    testid: "models-admin-only",
    text: "Retraining and changing the active model are for admins.",
  });
  adminsOnly.hidden = admin;

  // While another kind's retrain runs, this kind's Retrain waits: the readiness line is read
  // again until it ends, so the button comes back without a reload.
  let followingOther = false;
  async function followOtherRetrain(): Promise<void> {
    if (followingOther) return;
    followingOther = true;
    try {
      for (;;) {
        await sleep(OTHER_RETRAIN_POLL_MS, abort.signal);
        const readiness = await modelsApi.retrainReadiness(abort.signal, kind);
        form.showReadiness(readiness);
        if (!readiness.other_retrain) return;
      }
    } catch {
      // The page went (aborted), or the server is away: the next visit reads it again.
    } finally {
      followingOther = false;
    }
  }

  async function refresh(newest = false): Promise<void> {
    try {
      const [models, events, readiness] = await Promise.all([
        modelsApi.listModels(abort.signal, kind),
        modelsApi.listEvents(abort.signal, kind),
        modelsApi.retrainReadiness(abort.signal, kind),
      ]);
      table.show(models);
      form.showReadiness(readiness);
      if (readiness.other_retrain) void followOtherRetrain();
      history.show(events);
      // The model asked for, else the active one (its card says when it has no curve: the
      // newest curve shown instead was read as the active model's); after a retrain, the new
      // model.
      const active = models.find((m) => m.active);
      const withCurve = models.filter((m) => m.has_curve).sort((a, b) => b.version - a.version)[0];
      const asked = newest ? withCurve : models.find((m) => m.id === curve.shownId);
      curve.show(asked ?? active ?? withCurve ?? models[0]);
    } catch (error) {
      if (!abort.signal.aborted) table.showError(`Could not load the models: ${String(error)}`);
    }
  }

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
      adminsOnly,
      table.element,
      curve.element,
      form.element,
      history.element,
    ),
  );

  void refresh();
  void modelsApi
    .latestRetrainJob(abort.signal, kind)
    .then((job) => {
      if (job) form.resume(job);
    })
    .catch(() => {
      // The list shows any load error; the last job is only a convenience.
    });

  return () => abort.abort();
}
