// The workflow bar's account of the scene: its state badge, who annotates it, the reviewer's
// comment when it came back, a note on what to do next, and the workflow history.
import type { CurrentUser, SceneWorkflow, WorkflowEvent } from "@holiscene/schema";
import { stateBadge } from "../../api/workflow";
import { button, el, formatTime } from "../../dom";

const ACTION_TEXT: Record<WorkflowEvent["action"], string> = {
  import: "imported",
  predict: "predicted",
  claim: "took it",
  release: "gave it back",
  reopen: "reopened it",
  submit: "submitted",
  withdraw: "took the submission back",
  accept: "accepted",
  reject: "rejected",
  second_annotation: "asked for a second annotation",
  archive: "archived it",
  unarchive: "restored it from the archive",
};

function eventLine(event: WorkflowEvent): HTMLElement {
  return el(
    "li",
    { attrs: { "data-action": event.action } },
    `${formatTime(event.at)} · ${event.actor} ${ACTION_TEXT[event.action]} (revision ${event.revision})`,
    event.comment ? el("q", { text: event.comment }) : null,
  );
}

/** What the scene's state asks of the user now. */
export interface NoteInputs {
  flow: SceneWorkflow;
  /** Unsaved edits. */
  pending: number;
  /** Edits an earlier visit left unsaved are offered, neither restored nor discarded yet. */
  recovered?: boolean;
  me: CurrentUser | null;
  /** How many objects have a supporter a person set, as a sentence. */
  labelled: string;
}

export function noteText({ flow, pending, recovered, me, labelled }: NoteInputs): string {
  const name = me?.name;
  if (flow.archived_by != null)
    return (
      `Archived by ${flow.archived_by}: out of the scene list, "Next scene" and retraining, ` +
      "and read only; every revision is kept. An admin's Unarchive brings it back."
    );
  switch (flow.state) {
    case "new":
      // Imported without a pipeline run, or its run failed: the page waits while one runs.
      return `The pipeline has not run on this scene: "Run pipeline again" makes its guesses. ${labelled}`;
    case "predicted":
      // Labels imported with the photo are people's, so "nobody checked it" would be wrong.
      return `Not reviewed here yet. ${labelled} Editing takes the scene.`;
    case "in_annotation":
      if (flow.assignee !== name) return `${flow.assignee ?? "Someone"} is annotating this scene.`;
      if (recovered)
        return "Restore or discard the unsaved changes from your last visit (below), then submit.";
      return pending > 0
        ? "Save your changes, then submit the scene for review."
        : `When every supporter is right, submit the scene for review. ${labelled}`;
    case "submitted":
      if (flow.assignee === name && !me?.local_mode)
        return 'Submitted: a reviewer will accept it or send it back to you. Until then, "Take back" lets you change it.';
      return `Submitted by ${flow.assignee ?? "an annotator"} at revision ${flow.revision}. ${labelled}`;
    case "accepted":
      return `Accepted. ${labelled}`;
    case "rejected":
      return flow.assignee === name
        ? "Sent back to you: fix what the reviewer says, then submit again."
        : `Sent back to ${flow.assignee ?? "the annotator"}.`;
  }
}

export interface WorkflowStatus {
  /** The state badge and the assignee, for the bar's first line. */
  badge: HTMLElement;
  who: HTMLElement;
  comment: HTMLElement;
  note: HTMLElement;
  /** What the annotator changed since the last rejection, or on a first review since they
   * took the scene: a link to the revision history's diff. */
  sinceRejection: HTMLElement;
  history: HTMLElement;
  show(flow: SceneWorkflow, note: string, me: CurrentUser | null): void;
}

/** The scene's last rejection, if it had one. */
const lastRejection = (flow: SceneWorkflow) =>
  [...flow.events].reverse().find((e) => e.action === "reject");

/** The revision a reviewer last sent the scene back at, while the scene has moved on from it
 * in the same round of review (fixed, resubmitted): null otherwise. */
function rejectedAt(flow: SceneWorkflow): number | null {
  if (flow.state === "accepted" || flow.state === "predicted" || flow.state === "new") return null;
  const rejection = lastRejection(flow);
  return rejection && flow.revision > rejection.revision ? rejection.revision : null;
}

/** Where a reviewer starts: what changed since the scene was sent back, or, on its first
 * review, since its annotator took it (null: nothing to show). */
export function reviewStart(flow: SceneWorkflow): { revision: number; text: string } | null {
  const rejected = rejectedAt(flow);
  if (rejected !== null)
    return {
      revision: rejected,
      text: `What changed since it was sent back (revision ${rejected})`,
    };
  if (flow.state !== "submitted") return null;
  // A submission taken back and submitted again was still one taking of the scene.
  const taken = [...flow.events]
    .reverse()
    .find((e) => e.to_state === "in_annotation" && e.action !== "withdraw");
  if (!taken || flow.revision <= taken.revision) return null;
  const who = flow.assignee ?? "the annotator";
  return {
    revision: taken.revision,
    text: `What ${who} changed since taking it (revision ${taken.revision})`,
  };
}

/** `showSince(n)`: open the revision history at what changed since revision n. */
export function workflowStatus(showSince: (revision: number) => void): WorkflowStatus {
  const badge = el("span", { className: "state-badge", testid: "workflow-state" });
  const who = el("span", { className: "workflow-who", testid: "workflow-assignee" });
  const comment = el("div", {
    className: "alert alert--conflict review-comment",
    testid: "review-comment",
    attrs: { role: "note", hidden: true },
  });
  const note = el("p", { className: "workflow-note", testid: "workflow-note" });
  let since: number | null = null;
  // A reviewer judging a resubmitted scene looks at what the annotator changed first.
  const sinceRejection = button("", {
    className: "link-button",
    testid: "since-rejection",
    onClick: () => {
      if (since !== null) showSince(since);
    },
  });
  const events = el("ol", { className: "workflow-events", testid: "workflow-events" });
  const history = el(
    "details",
    { className: "history" },
    el("summary", { text: "Workflow history" }),
    events,
  );
  const show = (flow: SceneWorkflow, noteLine: string, me: CurrentUser | null) => {
    const state = flow.state;
    // Archived, the state is where it will be again once restored: both are said.
    const shown = stateBadge(state, flow.archived_by != null);
    badge.textContent = shown.text;
    badge.dataset.state = shown.key;
    who.textContent = flow.assignee
      ? `${state === "in_annotation" ? "annotated by" : "annotator:"} ${flow.assignee}`
      : "";
    if (flow.annotation_round > 1)
      who.textContent += ` · annotation round ${flow.annotation_round}`;
    // Resubmitted, the comment is the scene's no longer; a reviewer (not its annotator) still
    // sees what was asked, to check it was done.
    const rejection = lastRejection(flow);
    const asked =
      flow.review_comment ??
      (flow.state === "submitted" && flow.assignee !== me?.name ? rejection?.comment : null);
    comment.hidden = !asked;
    comment.replaceChildren(
      el("strong", {
        text: flow.review_comment
          ? `Rejected by ${rejection?.actor ?? "a reviewer"}: `
          : `Asked when sent back by ${rejection?.actor ?? "a reviewer"} (revision ${rejection?.revision}): `,
      }),
      el("span", { text: asked ?? "", testid: "review-comment-text" }),
    );
    note.textContent = noteLine;
    const start = reviewStart(flow);
    since = start?.revision ?? null;
    sinceRejection.hidden = start === null;
    sinceRejection.textContent = start?.text ?? "";
    events.replaceChildren(...flow.events.map(eventLine));
  };
  return { badge, who, comment, note, sinceRejection, history, show };
}
