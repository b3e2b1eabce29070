// The scene's place in the annotation workflow, on the scene page: its state, who annotates
// it, the reviewer's comment when it came back, and the actions the user's role allows now
// (take, submit, accept, reject with a comment, ask for a second annotation), with keys:
// Shift+Enter does the main step (submit, or accept for a reviewer), Shift+X rejects, ">" takes
// the next scene (the support editor has N, Shift+A and Shift+R already).
import type { SceneWorkflow, WorkflowEvent } from "@holiscene/schema";
import { ApiError } from "../../api/errors";
import { stateLabel, workflowApi } from "../../api/workflow";
import { button, el, formatTime, hiddenErrorAlert } from "../../dom";
import { registerShortcut } from "../../shortcuts";
import { getCurrentUser, hasRole } from "../../state/currentUser";
import type { SceneSession } from "../../state/sceneSession";
import { nextSceneControl } from "./nextScene";
import "./workflow.css";

const ACTION_TEXT: Record<WorkflowEvent["action"], string> = {
  import: "imported",
  predict: "predicted",
  claim: "took it",
  reopen: "reopened it",
  submit: "submitted",
  accept: "accepted",
  reject: "rejected",
  second_annotation: "asked for a second annotation",
};

function eventLine(event: WorkflowEvent): HTMLElement {
  return el(
    "li",
    { attrs: { "data-action": event.action } },
    `${formatTime(event.at)} · ${event.actor} ${ACTION_TEXT[event.action]} (revision ${event.revision})`,
    event.comment ? el("q", { text: event.comment }) : null,
  );
}

export function mountWorkflowBar(container: HTMLElement, session: SceneSession): () => void {
  const abort = new AbortController();
  let flow: SceneWorkflow | null = null;
  let busy = false;

  const badge = el("span", { className: "state-badge", testid: "workflow-state" });
  const who = el("span", { className: "workflow-who", testid: "workflow-assignee" });
  const next = nextSceneControl(">");
  const comment = el("div", {
    className: "alert alert--conflict review-comment",
    testid: "review-comment",
    attrs: { role: "note", hidden: true },
  });
  const note = el("p", { className: "workflow-note", testid: "workflow-note" });
  const error = hiddenErrorAlert("workflow-error");
  const actionButton = (text: string, testid: string, title: string, primary = false) =>
    button(text, { className: primary ? "primary" : "", testid, title, hidden: true });
  const take = actionButton("Start annotating", "workflow-take", "Take this scene for annotation");
  const submit = actionButton("Submit for review", "workflow-submit", "Submit (Shift+Enter)", true);
  const accept = actionButton("Accept", "workflow-accept", "Accept (Shift+Enter)", true);
  const reject = actionButton("Reject…", "workflow-reject", "Reject with a comment (Shift+X)");
  const again = actionButton(
    "Ask for a second annotation",
    "workflow-second",
    "Reset the supports to the pipeline's guesses and have another annotator label it",
  );
  const rejectText = el("textarea", {
    testid: "reject-comment",
    attrs: {
      rows: 3,
      maxlength: 2000,
      placeholder: "What went wrong? The annotator sees this.",
      "aria-label": "Rejection comment",
    },
  });
  const rejectSend = button("Send back to the annotator", {
    className: "primary",
    testid: "reject-send",
  });
  const rejectCancel = button("Cancel", { testid: "reject-cancel" });
  const rejectBox = el(
    "div",
    { className: "reject-box", testid: "reject-box", attrs: { hidden: true } },
    rejectText,
    el("div", { className: "form-actions" }, rejectSend, rejectCancel),
  );
  const events = el("ol", { className: "workflow-events", testid: "workflow-events" });
  container.replaceChildren(
    el(
      "section",
      { className: "workflow-bar", testid: "workflow-bar", attrs: { "aria-label": "Workflow" } },
      el(
        "div",
        { className: "workflow-line" },
        badge,
        who,
        el("span", { className: "spacer" }),
        next.element,
      ),
      comment,
      note,
      el("div", { className: "workflow-actions" }, take, submit, accept, reject, again),
      rejectBox,
      error,
      el("details", { className: "history" }, el("summary", { text: "Workflow history" }), events),
    ),
  );

  const me = () => getCurrentUser();
  const mine = () => flow !== null && flow.assignee === me()?.name;
  const canSubmit = () =>
    flow?.state === "in_annotation" && mine() && hasRole("annotator") && !busy;
  const canReview = () =>
    flow?.state === "submitted" &&
    hasRole("reviewer") &&
    (!mine() || me()?.local_mode === true) &&
    !busy;

  const render = () => {
    if (!flow) return;
    const state = flow.state;
    container.dataset.state = state;
    badge.textContent = stateLabel(state);
    badge.dataset.state = state;
    who.textContent = flow.assignee
      ? `${state === "in_annotation" ? "annotated by" : "annotator:"} ${flow.assignee}`
      : "";
    if (flow.annotation_round > 1)
      who.textContent += ` · annotation round ${flow.annotation_round}`;
    comment.hidden = !flow.review_comment;
    const rejection = [...flow.events].reverse().find((e) => e.action === "reject");
    comment.replaceChildren(
      el("strong", { text: `Rejected by ${rejection?.actor ?? "a reviewer"}: ` }),
      el("span", { text: flow.review_comment ?? "", testid: "review-comment-text" }),
    );
    const pending = session.unsavedCount;
    const annotator = hasRole("annotator");
    take.hidden = !(
      annotator &&
      (state === "new" || state === "predicted" || (state === "rejected" && mine()))
    );
    take.textContent = state === "rejected" ? "Reopen for changes" : "Start annotating";
    submit.hidden = !(state === "in_annotation" && mine());
    submit.disabled = !canSubmit() || pending > 0;
    submit.title =
      pending > 0 ? "Save your changes first" : "Submit this revision for review (Shift+Enter)";
    const reviewing = canReview();
    accept.hidden = reject.hidden = !reviewing;
    accept.disabled = reject.disabled = busy;
    if (!reviewing) rejectBox.hidden = true;
    again.hidden = !(hasRole("reviewer") && (state === "submitted" || state === "accepted"));
    again.disabled = busy;
    note.textContent = noteText(flow, pending);
    events.replaceChildren(...flow.events.map(eventLine));
  };

  const noteText = (current: SceneWorkflow, pending: number): string => {
    const name = me()?.name;
    const manual = (session.doc.scene.supports ?? []).filter((s) => s.source === "manual").length;
    const labelled = `${manual} of ${session.objects.length} objects have a supporter set by a person.`;
    switch (current.state) {
      case "new":
        return "The pipeline has not finished on this scene yet.";
      case "predicted":
        return "The pipeline's guesses, not checked by anyone yet. Editing takes the scene.";
      case "in_annotation":
        if (current.assignee !== name)
          return `${current.assignee ?? "Someone"} is annotating this scene.`;
        return pending > 0
          ? "Save your changes, then submit the scene for review."
          : `When every supporter is right, submit the scene for review. ${labelled}`;
      case "submitted":
        if (current.assignee === name && !me()?.local_mode)
          return "Submitted: waiting for another reviewer.";
        return `Submitted by ${current.assignee ?? "an annotator"} at revision ${current.revision}. ${labelled}`;
      case "accepted":
        return `Accepted. ${labelled}`;
      case "rejected":
        return current.assignee === name
          ? "Sent back to you: fix what the reviewer says, then submit again."
          : `Sent back to ${current.assignee ?? "the annotator"}.`;
    }
  };

  const load = async () => {
    try {
      flow = await workflowApi.get(session.sceneId, abort.signal);
      session.setWorkflow(flow); // submitted and accepted scenes are read only
      render();
    } catch (err) {
      if (!abort.signal.aborted) showError(err);
    }
  };

  const showError = (err: unknown) => {
    error.hidden = false;
    error.textContent = err instanceof ApiError ? err.message : String(err);
  };

  const act = async (action: () => Promise<unknown>, reloadDocument = false) => {
    if (busy) return;
    busy = true;
    error.hidden = true;
    render();
    try {
      await action();
      if (reloadDocument) await session.reloadLatest();
    } catch (err) {
      showError(err);
    } finally {
      busy = false;
      await load();
    }
  };

  const revision = () => session.doc.revision;
  take.addEventListener("click", () => void act(() => workflowApi.take(session.sceneId)));
  submit.addEventListener(
    "click",
    () => void act(() => workflowApi.submit(session.sceneId, revision())),
  );
  accept.addEventListener(
    "click",
    () => void act(() => workflowApi.accept(session.sceneId, revision())),
  );
  const openReject = () => {
    rejectBox.hidden = false;
    rejectText.focus();
  };
  reject.addEventListener("click", openReject);
  rejectCancel.addEventListener("click", () => {
    rejectBox.hidden = true;
  });
  rejectSend.addEventListener("click", () => {
    const text = rejectText.value.trim();
    if (!text) {
      showError("Say what went wrong: the annotator sees this comment.");
      rejectText.focus();
      return;
    }
    void act(async () => {
      await workflowApi.reject(session.sceneId, revision(), text);
      rejectText.value = "";
      rejectBox.hidden = true;
    });
  });
  again.addEventListener("click", () => {
    const question =
      "Reset this scene's supports to the pipeline's guesses so that another annotator labels it independently?";
    if (window.confirm(question))
      void act(() => workflowApi.secondAnnotation(session.sceneId, revision()), true);
  });

  const removers = [
    registerShortcut({
      keys: "Shift+Enter",
      description: "Submit the scene for review",
      scope: "Workflow",
      run: () => submit.click(),
      enabled: () => !submit.hidden && !submit.disabled,
    }),
    registerShortcut({
      keys: "Shift+Enter",
      description: "Accept the submitted scene (reviewers)",
      scope: "Workflow",
      run: () => accept.click(),
      enabled: () => !accept.hidden && !accept.disabled,
    }),
    registerShortcut({
      keys: "Shift+X",
      description: "Reject the submitted scene with a comment (reviewers)",
      scope: "Workflow",
      run: openReject,
      enabled: () => !reject.hidden && !reject.disabled,
    }),
  ];
  let shownRevision = session.doc.revision;
  const unsubscribe = session.subscribe((change) => {
    if (change === "document" && session.doc.revision !== shownRevision) {
      shownRevision = session.doc.revision;
      void load(); // a save may have taken the scene
    } else if (change === "edits") {
      render();
    } else if (change === "lock" && session.saveState.kind === "error") {
      void load(); // a save was refused: the scene's state may have changed meanwhile
    }
  });
  void load();
  return () => {
    abort.abort();
    unsubscribe();
    next.dispose();
    for (const remove of removers) remove();
  };
}
