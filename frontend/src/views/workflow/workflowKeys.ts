// The workflow bar's keys: Shift+Enter does the main step (submit, or accept for a reviewer),
// Shift+X opens the rejection box. Each works only while its button is offered; a keystroke
// that locks the scene is asked about first (the button's own questions, or a plain one).
import { registerShortcut } from "../../shortcuts";
import type { WorkflowActions } from "./workflowActions";

/** Register the keys; returns the function that removes them. */
export function workflowKeys(actions: WorkflowActions): () => void {
  const { submit, accept, reject } = actions;
  const removers = [
    registerShortcut({
      keys: "Shift+Enter",
      description: "Submit the scene for review",
      scope: "Workflow",
      run: actions.submitByKey,
      enabled: () => !submit.hidden && !submit.disabled,
    }),
    registerShortcut({
      keys: "Shift+Enter",
      description: "Accept the submitted scene (reviewers)",
      scope: "Workflow",
      run: actions.acceptByKey,
      enabled: () => !accept.hidden && !accept.disabled,
      listed: actions.forReviewer,
    }),
    registerShortcut({
      keys: "Shift+X",
      description: "Reject the submitted scene with a comment (reviewers)",
      scope: "Workflow",
      run: actions.openReject,
      enabled: () => !reject.hidden && !reject.disabled,
      listed: actions.forReviewer,
    }),
  ];
  return () => {
    for (const remove of removers) remove();
  };
}
