// What the workflow bar asks of the annotator holding the scene.
import type { CurrentUser, SceneWorkflow } from "@holiscene/schema";
import { describe, expect, it } from "vitest";
import { noteText, reviewStart } from "./workflowStatus";

const ann: CurrentUser = { name: "ann", role: "annotator", local_mode: false };
const flow = {
  state: "in_annotation",
  assignee: "ann",
  events: [],
  revision: 3,
} as unknown as SceneWorkflow;

describe("the workflow note of the scene's annotator", () => {
  it("asks to submit when nothing is waiting", () => {
    expect(noteText({ flow, pending: 0, me: ann, labelled: "2 of 3." })).toBe(
      "When every supporter is right, submit the scene for review. 2 of 3.",
    );
  });

  it("asks to save first, and to settle a last visit's edits before that", () => {
    expect(noteText({ flow, pending: 2, me: ann, labelled: "" })).toBe(
      "Save your changes, then submit the scene for review.",
    );
    expect(noteText({ flow, pending: 0, recovered: true, me: ann, labelled: "" })).toMatch(
      /^Restore or discard the unsaved changes from your last visit/,
    );
  });
});

describe("where a reviewer starts", () => {
  const event = (action: string, to_state: string, revision: number, comment?: string) => ({
    action,
    to_state,
    revision,
    comment: comment ?? null,
    actor: action === "reject" ? "rita" : "ann",
  });
  const submitted = (events: object[], revision: number) =>
    ({ state: "submitted", assignee: "ann", events, revision }) as unknown as SceneWorkflow;

  it("on a first review: what the annotator changed since taking the scene", () => {
    const flow = submitted(
      [
        event("predict", "predicted", 2),
        event("claim", "in_annotation", 2),
        event("submit", "submitted", 5),
      ],
      5,
    );
    expect(reviewStart(flow)).toEqual({
      revision: 2,
      text: "What ann changed since taking it (revision 2)",
    });
  });

  it("a submission taken back and submitted again counts from the taking, not the taking back", () => {
    const flow = submitted(
      [
        event("claim", "in_annotation", 2),
        event("submit", "submitted", 5),
        event("withdraw", "in_annotation", 5),
        event("submit", "submitted", 6),
      ],
      6,
    );
    expect(reviewStart(flow)?.revision).toBe(2);
  });

  it("after a rejection: what changed since it was sent back", () => {
    const flow = submitted(
      [
        event("claim", "in_annotation", 2),
        event("submit", "submitted", 5),
        event("reject", "rejected", 5, "check o3"),
        event("claim", "in_annotation", 5),
        event("submit", "submitted", 7),
      ],
      7,
    );
    expect(reviewStart(flow)?.revision).toBe(5);
    expect(reviewStart(flow)?.text).toBe("What changed since it was sent back (revision 5)");
  });

  it("nothing when the annotator changed nothing, or the scene is not submitted", () => {
    const untouched = submitted([event("claim", "in_annotation", 4)], 4);
    expect(reviewStart(untouched)).toBeNull();
    expect(reviewStart({ ...untouched, state: "accepted" } as SceneWorkflow)).toBeNull();
  });
});
