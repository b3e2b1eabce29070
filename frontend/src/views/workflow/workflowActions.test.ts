// Who is offered "Give back": the scene's annotator (not when a reviewer sent it back to be
// fixed) and admins; never in local single-user mode. "Take over" and "Take back" likewise.
import type { CurrentUser, SceneWorkflow, WorkflowEvent } from "@holiscene/schema";
import { describe, expect, it } from "vitest";
import { actionState } from "./workflowActions";

const user = (name: string, role: CurrentUser["role"], local_mode = false): CurrentUser => ({
  name,
  role,
  local_mode,
});

const event = (action: WorkflowEvent["action"], annotation_round = 1): WorkflowEvent =>
  ({ action, annotation_round, actor: "x", at: "2026-12-05T00:00:00Z" }) as WorkflowEvent;

const flow = (
  state: SceneWorkflow["state"],
  assignee: string | null,
  events: WorkflowEvent[] = [],
  annotation_round = 1,
): SceneWorkflow =>
  ({ state, assignee, events, annotation_round, revision: 3, scene_id: "s" }) as SceneWorkflow;

const canRelease = (f: SceneWorkflow, me: CurrentUser) => actionState(f, me, 0, false).canRelease;

describe("give back", () => {
  it("is offered to the scene's annotator and to admins while it is in annotation", () => {
    const taken = flow("in_annotation", "ann", [event("claim")]);
    expect(canRelease(taken, user("ann", "annotator"))).toBe(true);
    expect(canRelease(taken, user("bob", "annotator"))).toBe(false);
    expect(canRelease(taken, user("rita", "reviewer"))).toBe(false);
    expect(canRelease(taken, user("ada", "admin"))).toBe(true);
    expect(canRelease(flow("submitted", "ann"), user("ann", "annotator"))).toBe(false);
    expect(canRelease(flow("predicted", null), user("ann", "annotator"))).toBe(false);
  });

  it("is not offered for a scene sent back in this round, nor in local mode", () => {
    const fixing = flow("in_annotation", "ann", [
      event("submit"),
      event("reject"),
      event("reopen"),
    ]);
    expect(canRelease(fixing, user("ann", "annotator"))).toBe(false);
    expect(canRelease(fixing, user("ada", "admin"))).toBe(true);
    const secondRound = flow("in_annotation", "ann", [event("reject", 1), event("claim", 2)], 2);
    expect(canRelease(secondRound, user("ann", "annotator"))).toBe(true);
    const local = flow("in_annotation", "local");
    expect(canRelease(local, user("local", "admin", true))).toBe(false);
  });
});

describe("take over", () => {
  it("is offered to admins on a scene someone else annotates or fixes, not to its annotator", () => {
    const taken = flow("in_annotation", "ann");
    const takeOver = (f: SceneWorkflow, me: CurrentUser) =>
      actionState(f, me, 0, false).canTakeOver;
    expect(takeOver(taken, user("ada", "admin"))).toBe(true);
    expect(takeOver(flow("rejected", "ann"), user("ada", "admin"))).toBe(true);
    expect(takeOver(taken, user("ann", "annotator"))).toBe(false);
    expect(takeOver(taken, user("rita", "reviewer"))).toBe(false);
    expect(takeOver(flow("in_annotation", "ada"), user("ada", "admin"))).toBe(false);
    expect(takeOver(flow("submitted", "ann"), user("ada", "admin"))).toBe(false);
  });
});

describe("take back", () => {
  it("is offered to the annotator who submitted, until a reviewer decides", () => {
    const takeBack = (f: SceneWorkflow, me: CurrentUser) =>
      actionState(f, me, 0, false).canWithdraw;
    const submitted = flow("submitted", "ann", [event("submit")]);
    expect(takeBack(submitted, user("ann", "annotator"))).toBe(true);
    expect(takeBack(submitted, user("bob", "annotator"))).toBe(false);
    expect(takeBack(submitted, user("rita", "reviewer"))).toBe(false);
    expect(takeBack(flow("accepted", "ann"), user("ann", "annotator"))).toBe(false);
    expect(takeBack(flow("rejected", "ann"), user("ann", "annotator"))).toBe(false);
    expect(takeBack(flow("in_annotation", "ann"), user("ann", "annotator"))).toBe(false);
  });
});
