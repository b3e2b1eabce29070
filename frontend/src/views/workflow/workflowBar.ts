// The scene's place in the annotation workflow, on the scene page: its state, who annotates
// it, the reviewer's comment when it came back, and the actions the user's role allows now
// (take, give back, submit, accept, reject with a comment, ask for a second annotation), with keys:
// Shift+Enter does the main step (submit, or accept for a reviewer), Shift+X rejects, ">" takes
// the next scene (the support editor has N, Shift+A and Shift+R already).

import type { SceneWorkflow } from "@holiscene/schema";
import { deferred } from "../../afterPaint";
import { ApiError } from "../../api/errors";
import { workflowApi } from "../../api/workflow";
import { el, hiddenErrorAlert } from "../../dom";
import { getCurrentUser } from "../../state/currentUser";
import { plural, type SceneSession } from "../../state/sceneSession";
import { everyWhileVisible } from "../common/everyWhileVisible";
import { glbOutOfDate } from "../scene/glbStaleness";
import { nextSceneControl } from "./nextScene";
import { unsettledSupports } from "./submitConcerns";
import { actionState, workflowActions } from "./workflowActions";
import { workflowKeys } from "./workflowKeys";
import { noteText, workflowStatus } from "./workflowStatus";
import "./workflow.css";

// Its parts: workflowStatus (state, assignee, comment, note, history), workflowActions (the
// buttons and the reject box) and workflowKeys; this bar loads the scene's workflow, runs the
// actions one at a time and shows the outcome in both.

const WORKFLOW_CHECK_MS = 10_000;

/** `showSince(n)`: open the revision history at what changed since revision n. */
export function mountWorkflowBar(
  container: HTMLElement,
  session: SceneSession,
  showSince: (revision: number) => void,
): () => void {
  const abort = new AbortController();
  let flow: SceneWorkflow | null = null;
  let busy = false;

  const status = workflowStatus(showSince);
  // Next scene from a scene this person took and left as it was gives it back first: it
  // waits for the next annotator instead of staying theirs, untouched (two clicks of Next
  // scene kept two scenes "in annotation" with nobody working on them).
  const giveBackUntouched = async () => {
    const took = flow?.events.at(-1);
    const untouched =
      flow?.state === "in_annotation" &&
      flow.assignee === getCurrentUser()?.name &&
      took?.action === "claim" &&
      took.revision === revision() &&
      session.unsavedCount === 0 &&
      session.saveState.kind !== "saving";
    if (!untouched) return null;
    await workflowApi.release(session.sceneId, revision());
    return `"${session.doc.scene.name}" went back to the queue: you took it and changed nothing.`;
  };
  const next = nextSceneControl(
    { take: ">", review: "Shift+ArrowRight", current: session.sceneId },
    giveBackUntouched,
  );
  const error = hiddenErrorAlert("workflow-error");
  const revision = () => session.doc.revision;
  const personLabels = () =>
    (session.doc.scene.supports ?? []).filter((s) => s.source === "manual").length;
  const labelledText = () => {
    const count = personLabels();
    return `${count} of ${plural(session.objects.length, "object")} ${count === 1 ? "has" : "have"} a supporter set by a person.`;
  };
  // What scene.glb lacks of the scene ("" when nothing, or when the server cannot say: the
  // question is a courtesy, not a gate).
  const outOfDate3d = () =>
    glbOutOfDate(session.sceneId, session.doc, abort.signal).catch(() => "");
  const actions = workflowActions({
    onTake: () => {
      const assignee = flow?.assignee;
      const mine = assignee === getCurrentUser()?.name;
      const question = `${assignee} is annotating this scene. Take it over? Their next save is refused; what they saved stays.`;
      if (assignee && !mine && !window.confirm(question)) return;
      void act(() => workflowApi.take(session.sceneId));
    },
    onSubmit: (byKey = false) =>
      void (async () => {
        // What a reviewer would send the scene back for, asked about in one question: objects
        // without a supporter, suggestions not accepted, a 3D scene older than the labels, nothing
        // checked by a person.
        const concerns = unsettledSupports(session);
        const lacks = await outOfDate3d();
        if (lacks !== "")
          concerns.push(
            `The 3D scene was made before these changes: ${lacks}. "Re-place objects" in the ` +
              "3D panel brings it up to date; once the scene is submitted nobody can.",
          );
        if (personLabels() === 0 && session.objects.length > 0)
          concerns.push(
            `None of the ${session.objects.length} objects has a supporter set by a person: ` +
              "each is the pipeline's guess, unchecked.",
          );
        const locked = "It is read only until a reviewer accepts it or sends it back.";
        const question =
          concerns.length > 0
            ? `${concerns.map((c) => `• ${c}`).join("\n")}\n\nSubmit for review anyway? ${locked}`
            : `Submit this scene for review? ${locked}`;
        // A click with nothing to say submits; a keystroke always asks (one key is final).
        if ((concerns.length > 0 || byKey) && !window.confirm(question)) return;
        await act(() => workflowApi.submit(session.sceneId, revision()));
      })(),
    onRelease: () => {
      const question =
        "Give this scene back? It waits in the queue for the next annotator; every saved revision stays in its history.";
      if (window.confirm(question))
        void act(() => workflowApi.release(session.sceneId, revision()));
    },
    onWithdraw: () => void act(() => workflowApi.withdraw(session.sceneId, revision())),
    onAccept: () =>
      void (async () => {
        const lacks = await outOfDate3d();
        const stale =
          `The 3D scene lacks the annotator's last changes (${lacks}), and an accepted scene ` +
          "cannot be re-placed: rejecting it with a comment asks for that. Accept anyway?";
        if (lacks !== "" && !window.confirm(stale)) return;
        // Asked by click too: an accepted scene can no longer be edited by anyone.
        const plain = `Accept this scene? Its labels become final. ${labelledText()}`;
        if (lacks === "" && !window.confirm(plain)) return;
        await act(() => workflowApi.accept(session.sceneId, revision()));
      })(),
    onReject: (text) =>
      void act(async () => {
        await workflowApi.reject(session.sceneId, revision(), text);
        actions.rejected();
      }),
    onEmptyReject: () => showError("Say what went wrong: the annotator sees this comment."),
    onArchive: () => {
      // Someone holding the scene can save nothing more until it is restored: said first.
      const holder =
        flow?.assignee && (flow.state === "in_annotation" || flow.state === "rejected")
          ? ` ${flow.assignee} is annotating it: their next save is refused (kept in their ` +
            "browser) until it is restored."
          : "";
      const question =
        `Archive "${session.doc.scene.name}"? It leaves the scene list, "Next scene", reviews, ` +
        "retraining and batch runs, and becomes read only. Every revision is kept, and an " +
        `admin can restore it (the list's Archived filter shows it).${holder}`;
      // The document is loaded again for its permission (read only now); no revision changed.
      if (window.confirm(question)) void act(() => workflowApi.archive(session.sceneId), true);
    },
    onUnarchive: () => void act(() => workflowApi.unarchive(session.sceneId), true),
    onSecondAnnotation: () => {
      const question =
        "Reset this scene's supports to the pipeline's guesses so that another annotator labels it independently?";
      if (window.confirm(question))
        void act(() => workflowApi.secondAnnotation(session.sceneId, revision()), true);
    },
  });
  container.replaceChildren(
    el(
      "section",
      { className: "workflow-bar", testid: "workflow-bar", attrs: { "aria-label": "Workflow" } },
      el(
        "div",
        { className: "workflow-line" },
        status.badge,
        status.who,
        el("span", { className: "spacer" }),
        next.element,
      ),
      status.comment,
      status.note,
      status.sinceRejection,
      actions.element,
      actions.rejectBox,
      error,
      status.history,
    ),
  );

  const me = () => getCurrentUser();

  const render = () => {
    if (!flow) return;
    container.dataset.state = flow.state;
    const pending = session.unsavedCount;
    const recovered = session.recovered !== null;
    const labelled = labelledText();
    status.show(flow, noteText({ flow, pending, recovered, me: me(), labelled }), me());
    actions.show(actionState(flow, me(), pending, busy, recovered));
  };

  const load = async (background = false) => {
    try {
      const loaded = await workflowApi.get(session.sceneId, abort.signal, background);
      // The same answer as before: nothing to redraw.
      if (background && JSON.stringify(flow) === JSON.stringify(loaded)) return;
      flow = loaded;
      session.setWorkflow(flow); // submitted and accepted scenes are read only
      render();
      // Someone else saved while this page may only watch (a reviewer, an annotator locked
      // out): show their revision, and the save bar says who changed what.
      if (background && !session.editable && loaded.revision > session.doc.revision)
        await session.reloadLatest();
    } catch (err) {
      if (!abort.signal.aborted && !background) showError(err);
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

  const removeKeys = workflowKeys(actions);
  let shownRevision = session.doc.revision;
  // After the new revision is drawn (its request would hold the redraw back).
  const loadLater = deferred(() => void load());
  const unsubscribe = session.subscribe((change) => {
    if (change === "document" && session.doc.revision !== shownRevision) {
      shownRevision = session.doc.revision;
      loadLater(); // a save may have taken the scene
    } else if (change === "edits" || change === "recovery") {
      render();
    } else if (change === "lock" && session.saveState.kind === "error") {
      void load(); // a save was refused: the scene's state may have changed meanwhile
    }
  });
  void load();
  // Someone else may submit, accept, reject or take the scene while this page is open: looked
  // at again every few seconds while the tab is visible, so the buttons and the lock follow.
  const stopWatching = everyWhileVisible(WORKFLOW_CHECK_MS, () => {
    if (!busy) void load(true);
  });
  return () => {
    stopWatching();
    loadLater.cancel();
    abort.abort();
    unsubscribe();
    next.dispose();
    removeKeys();
  };
}
