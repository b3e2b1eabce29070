// What the workflow bar asks of the annotator holding the scene.
import type { CurrentUser, SceneWorkflow } from "@holiscene/schema";
import { describe, expect, it } from "vitest";
import { noteText } from "./workflowStatus";

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
