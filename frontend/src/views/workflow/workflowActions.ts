// The workflow bar's buttons: take, give back, submit, take a submission back, accept, reject
// (with the comment box it opens) and "ask for a second annotation", each shown only when the user's role and the scene's state
// allow it. What they do is the bar's business (onTake, ...).
import type { CurrentUser, SceneWorkflow } from "@holiscene/schema";
import { button, el } from "../../dom";
import { hasRole } from "../../state/currentUser";

/** What the buttons may offer now. */
export interface ActionState {
  flow: SceneWorkflow;
  /** Unsaved edits (submitting waits for them). */
  pending: number;
  /** Edits an earlier visit left unsaved, neither restored nor discarded yet: submitting or
   * giving the scene back would strand them, so both wait for that choice. */
  recovered: boolean;
  /** An action is on its way. */
  busy: boolean;
  /** Takes: an annotator; reopens: the scene's own annotator. */
  annotator: boolean;
  mine: boolean;
  canSubmit: boolean;
  /** Take a submission back: its annotator, until a reviewer decides. */
  canWithdraw: boolean;
  /** Give the scene back to the queue: its annotator (or an admin), unless sent back to fix. */
  canRelease: boolean;
  /** An admin may take over a scene someone else annotates (edits alone do not). */
  canTakeOver: boolean;
  canReview: boolean;
  reviewer: boolean;
  admin: boolean;
}

/** What `me` may do with the scene now (busy: an action is on its way). */
export function actionState(
  flow: SceneWorkflow,
  me: CurrentUser | null,
  pending: number,
  busy: boolean,
  recovered = false,
): ActionState {
  const mine = flow.assignee === me?.name;
  const annotator = hasRole("annotator", me);
  const reviewer = hasRole("reviewer", me);
  const admin = hasRole("admin", me);
  const sentBack = flow.events.some(
    (e) => e.action === "reject" && e.annotation_round === flow.annotation_round,
  );
  return {
    flow,
    pending,
    recovered,
    busy,
    annotator,
    reviewer,
    admin,
    mine,
    canSubmit: flow.state === "in_annotation" && mine && annotator && !busy,
    canWithdraw: flow.state === "submitted" && mine && annotator,
    // In local mode one person plays every part: there is nobody to give it back to.
    canRelease:
      flow.state === "in_annotation" &&
      me?.local_mode !== true &&
      ((mine && annotator && !sentBack) || admin),
    canTakeOver:
      admin &&
      !mine &&
      flow.assignee !== null &&
      (flow.state === "in_annotation" || flow.state === "rejected"),
    canReview:
      flow.state === "submitted" && reviewer && (!mine || me?.local_mode === true) && !busy,
  };
}

export interface ActionHandlers {
  onTake(): void;
  /** `byKey`: one keystroke, so it is asked about even when nothing else is. */
  onSubmit(byKey?: boolean): void;
  onRelease(): void;
  onWithdraw(): void;
  /** Always asked first: an accepted scene is final. */
  onAccept(): void;
  /** The reviewer sends the comment (trimmed; never empty). */
  onReject(comment: string): void;
  /** "Send" with no comment. */
  onEmptyReject(): void;
  onSecondAnnotation(): void;
  /** An admin archives the scene (asked first) or restores it. */
  onArchive(): void;
  onUnarchive(): void;
}

export interface WorkflowActions {
  element: HTMLElement;
  rejectBox: HTMLElement;
  submit: HTMLButtonElement;
  accept: HTMLButtonElement;
  reject: HTMLButtonElement;
  /** Open the reject box, its comment focused. */
  openReject(): void;
  /** Submit (or accept) from the keyboard: as the button, asked first. */
  submitByKey(): void;
  acceptByKey(): void;
  /** Close the reject box and clear its comment (after a rejection went through). */
  rejected(): void;
  show(state: ActionState): void;
  /** Whether the person shown is a reviewer (their keys are listed in the help). */
  forReviewer(): boolean;
}

export function workflowActions(handlers: ActionHandlers): WorkflowActions {
  const actionButton = (text: string, testid: string, title: string, primary = false) =>
    button(text, { className: primary ? "primary" : "", testid, title, hidden: true });
  const take = actionButton("Start annotating", "workflow-take", "Take this scene for annotation");
  const submit = actionButton("Submit for review", "workflow-submit", "Submit (Shift+Enter)", true);
  const release = actionButton(
    "Give back",
    "workflow-release",
    "Put the scene back in the queue for another annotator (your saved changes stay)",
  );
  const withdraw = actionButton(
    "Take back",
    "workflow-withdraw",
    "Take the submission back to change it before a reviewer decides",
  );
  const accept = actionButton("Accept", "workflow-accept", "Accept (Shift+Enter)", true);
  const reject = actionButton("Reject…", "workflow-reject", "Reject with a comment (Shift+X)");
  const again = actionButton(
    "Ask for a second annotation",
    "workflow-second",
    "Reset the supports to the pipeline's guesses and have another annotator label it",
  );
  // An admin's: a scene nobody should work on leaves the lists, read only, kept whole.
  const archive = actionButton(
    "Archive scene",
    "workflow-archive",
    "Take this scene out of the lists and 'Next scene' (a junk photo, a duplicate); read " +
      "only, every revision kept, and an admin can restore it",
  );
  const unarchive = actionButton(
    "Unarchive",
    "workflow-unarchive",
    "Bring the archived scene back to the lists, as it was",
    true,
  );
  archive.addEventListener("click", handlers.onArchive);
  unarchive.addEventListener("click", handlers.onUnarchive);
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

  const openReject = () => {
    rejectBox.hidden = false;
    rejectText.focus();
  };
  take.addEventListener("click", handlers.onTake);
  submit.addEventListener("click", () => handlers.onSubmit());
  release.addEventListener("click", handlers.onRelease);
  withdraw.addEventListener("click", handlers.onWithdraw);
  accept.addEventListener("click", () => handlers.onAccept());
  reject.addEventListener("click", openReject);
  rejectCancel.addEventListener("click", () => {
    rejectBox.hidden = true;
  });
  rejectSend.addEventListener("click", () => {
    const text = rejectText.value.trim();
    if (!text) {
      handlers.onEmptyReject();
      rejectText.focus();
      return;
    }
    handlers.onReject(text);
  });
  again.addEventListener("click", handlers.onSecondAnnotation);

  let reviewer = false;
  const show = (now: ActionState) => {
    reviewer = now.reviewer;
    const { flow, pending, recovered, busy, mine } = now;
    const state = flow.state;
    const archived = flow.archived_by != null;
    archive.hidden = !now.admin || archived;
    unarchive.hidden = !now.admin || !archived;
    archive.disabled = unarchive.disabled = busy;
    // Archived: no step of the workflow until an admin restores it (the banner says so).
    if (archived) {
      for (const action of [take, submit, release, withdraw, accept, reject, again])
        action.hidden = true;
      rejectBox.hidden = true;
      return;
    }
    take.hidden = !(
      (now.annotator &&
        (state === "new" || state === "predicted" || (state === "rejected" && mine))) ||
      now.canTakeOver
    );
    take.textContent = now.canTakeOver
      ? `Take over from ${flow.assignee}`
      : state === "rejected"
        ? "Reopen for changes"
        : "Start annotating";
    take.title = now.canTakeOver
      ? `Make this scene yours: ${flow.assignee}'s next save is refused`
      : "Take this scene for annotation";
    submit.hidden = !(state === "in_annotation" && mine);
    const restoreFirst = "Restore or discard the unsaved changes from your last visit first";
    submit.disabled = !now.canSubmit || pending > 0 || recovered;
    submit.title = recovered
      ? restoreFirst
      : pending > 0
        ? "Save your changes first"
        : "Submit this revision for review (Shift+Enter)";
    release.hidden = !now.canRelease;
    release.disabled = busy || pending > 0 || recovered;
    release.title = recovered
      ? restoreFirst
      : pending > 0
        ? "Save or discard your changes first"
        : "Put the scene back in the queue for another annotator (your saved changes stay)";
    withdraw.hidden = !now.canWithdraw;
    withdraw.disabled = busy;
    accept.hidden = reject.hidden = !now.canReview;
    accept.disabled = reject.disabled = busy;
    if (!now.canReview) rejectBox.hidden = true;
    again.hidden = !(now.reviewer && (state === "submitted" || state === "accepted"));
    again.disabled = busy;
  };

  return {
    element: el(
      "div",
      { className: "workflow-actions" },
      take,
      submit,
      release,
      withdraw,
      accept,
      reject,
      again,
      unarchive,
      archive,
    ),
    rejectBox,
    submitByKey: () => handlers.onSubmit(true),
    acceptByKey: () => handlers.onAccept(),
    submit,
    accept,
    reject,
    openReject,
    rejected() {
      rejectText.value = "";
      rejectBox.hidden = true;
    },
    show,
    forReviewer: () => reviewer,
  };
}
