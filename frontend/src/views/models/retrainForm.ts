// The models page's retraining form: a new model of the kind trained on the server (a retrain
// job), its progress and log followed live; the page reloads the list when it ends.
import type { Job, RetrainReadiness } from "@holiscene/schema";
import { isFinished, pollJob } from "../../api/jobs";
import { modelsApi } from "../../api/models";
import { button, el, hiddenErrorAlert, labelledField } from "../../dom";
import type { ModelKind } from "../../router";
import { getAuthor } from "../../state/author";
import { jobProgress } from "../common/jobProgress";
import type { KindText } from "./kindText";
import { readinessText } from "./modelFigures";

const POLL_MS = 1000;

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

export interface RetrainFormInputs {
  kind: ModelKind;
  text: KindText;
  /** Stops following the job when the page goes. */
  signal: AbortSignal;
  /** A job ended: the page loads the models again. */
  onFinished(job: Job): Promise<void>;
  /** A retrain job shown started, ran on or ended (the curve card says it waits for it). */
  onJob?(job: Job): void;
}

export interface RetrainForm {
  element: HTMLFormElement;
  /** Show the kind's newest retrain job, and follow it while it runs. */
  resume(job: Job): void;
  /** The active model was changed by hand: a finished job's outcome line is history now. */
  activeChanged(): void;
  /** Say how many labelled scenes there are; Retrain waits until there are enough. */
  showReadiness(readiness: RetrainReadiness): void;
}

export function retrainForm({
  kind,
  text,
  signal,
  onFinished,
  onJob,
}: RetrainFormInputs): RetrainForm {
  const epochs = numberField(text.epochs[0], "epochs", text.epochs[1], 500);
  const synthetic = numberField(text.synthetic[0], "synthetic", text.synthetic[1], 20000);
  const retrain = button("Retrain", {
    className: "primary",
    testid: "retrain-button",
    type: "submit",
  });
  const cancel = button("Cancel retrain", {
    testid: "retrain-cancel",
    title: "Stop this retrain at its next step or epoch; no model is registered from it",
    onClick: () => void cancelShown(),
  });
  cancel.hidden = true;
  const retrainError = hiddenErrorAlert("retrain-error");
  const progress = jobProgress("retrain-progress");
  progress.element.hidden = true;
  const log = el("pre", { className: "job-log", testid: "retrain-log", attrs: { hidden: true } });
  const since = el("p", {
    className: "field-hint",
    testid: "retrain-since",
    text: "Since this job ended, the active model was changed by hand: the list above and the history below say which one is active.",
    attrs: { hidden: true },
  });
  const readiness = el("p", { className: "field-hint", testid: "retrain-readiness" });
  let shownJob: Job | null = null;
  let enoughScenes = true; // until the count arrives: the server refuses with a message anyway
  const form = el(
    "form",
    { className: "card", testid: "retrain-form" },
    el("h2", { text: "Retrain" }),
    el("p", { className: "field-hint", text: text.retrainHint }),
    readiness,
    el("div", { className: "field-grid" }, epochs.field, synthetic.field),
    el("div", { className: "form-actions" }, retrain, cancel),
    retrainError,
    progress.element,
    since,
    log,
  );

  // The finished job whose outcome a refused start put away: a late report of it (the page
  // reloading after it ended) must not bring it back under the refusal.
  let putAway: string | null = null;
  const showJob = (job: Job) => {
    if (job.id !== shownJob?.id) since.hidden = true;
    shownJob = job;
    onJob?.(job);
    if (job.id === putAway && isFinished(job)) return;
    progress.element.hidden = false;
    progress.update(job);
    log.hidden = job.log === "";
    const atBottom = log.scrollTop + log.clientHeight >= log.scrollHeight - 4;
    log.textContent = job.log;
    if (atBottom) log.scrollTop = log.scrollHeight;
    retrain.disabled = !isFinished(job) || !enoughScenes;
    cancel.hidden = isFinished(job);
  };

  const cancelShown = async () => {
    const job = shownJob;
    if (!job || !window.confirm("Cancel this retrain? Nothing of it is registered.")) return;
    cancel.disabled = true;
    try {
      showJob(await modelsApi.cancelRetrain(job.id));
    } catch (error) {
      retrainError.hidden = false;
      retrainError.textContent = `Could not cancel: ${String(error instanceof Error ? error.message : error)}`;
    } finally {
      cancel.disabled = false;
    }
  };

  const follow = async (job: Job) => {
    try {
      const final = await pollJob(job, { onUpdate: showJob, signal, intervalMs: POLL_MS });
      showJob(final);
      await onFinished(final);
    } catch (error) {
      if (!signal.aborted) {
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
      // An earlier job's outcome under this refusal would read as this attempt's.
      for (const old of [progress.element, log, since]) old.hidden = true;
      putAway = shownJob?.id ?? null;
    }
  });

  return {
    element: form,
    resume(job) {
      if (isFinished(job)) showJob(job);
      else void follow(job);
    },
    activeChanged() {
      if (shownJob && isFinished(shownJob)) since.hidden = false;
    },
    showReadiness(counted) {
      enoughScenes = counted.labelled_scenes >= counted.needed && counted.heldout_scenes > 0;
      const otherRunning = Boolean(counted.other_retrain);
      readiness.textContent = readinessText(counted);
      readiness.classList.toggle("is-warn", !enoughScenes || otherRunning);
      const running = shownJob !== null && !isFinished(shownJob);
      retrain.disabled = running || !enoughScenes || otherRunning;
      retrain.title = !enoughScenes
        ? "Label more scenes first (the line above says how many)"
        : otherRunning
          ? "Another retrain is running (the line above says which); this one can start when it ends"
          : "";
    },
  };
}
