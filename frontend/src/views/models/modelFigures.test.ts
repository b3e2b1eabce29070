// The question before a model is made active puts its figures beside the active model's.
import type { ModelInfo } from "@holiscene/schema";
import { describe, expect, it } from "vitest";
import { KIND_TEXT } from "./kindText";
import { heldoutText, promoteQuestion, readinessText } from "./modelFigures";

const model = (over: Partial<ModelInfo>): ModelInfo =>
  ({
    id: "m",
    version: 1,
    status: "accepted",
    active: false,
    heldout_accuracy: null,
    heldout_recall: null,
    heldout_items: null,
    heldout_scenes: 0,
    parent_version: null,
    parent_heldout_accuracy: null,
    parent_heldout_recall: null,
    validation_accuracy: null,
    ...over,
  }) as ModelInfo;

describe("the question before a model is made active", () => {
  const text = KIND_TEXT.relation;
  const active = model({ id: "a", version: 1, active: true, validation_accuracy: 0.991 });
  const retrained = model({
    id: "b",
    version: 2,
    status: "candidate",
    heldout_accuracy: 0.971,
    heldout_items: 34,
    heldout_scenes: 1,
    parent_version: 1,
    parent_heldout_accuracy: 0.971,
    validation_accuracy: 0.396,
  });

  it("gives both models' figures and how many scenes the held-out one rests on", () => {
    expect(promoteQuestion(retrained, active, text)).toBe(
      "Warning: its validation figure is 59.5 points below the active model's (each measured " +
        "on its own training run's validation scenes, not the same ones). " +
        "Make v2 the active model? Pipeline runs and suggestions use it from now on.\n\n" +
        "v2: held-out accuracy 97.1% (v1: 97.1%), on 34 labelled objects (1 held-out scene); " +
        "validation accuracy 39.6%\n" +
        "v1 (active now): held-out accuracy —; validation accuracy 99.1%",
    );
  });

  it("puts two warnings one space apart, and writes a detector's mAP as a column does", () => {
    const both = { ...retrained, heldout_items: 10 } as ModelInfo;
    expect(promoteQuestion(both, active, text)).toMatch(
      /not the same ones\)\. Its held-out figure rests on 10 items only: too few to tell two models apart\. Make v2/,
    );
    const detector = { ...retrained, heldout_recall: 0.5 } as ModelInfo;
    expect(promoteQuestion(detector, active, KIND_TEXT.detector)).toContain(
      "v2: held-out mAP@0.5 · recall 97.1% · 50.0%",
    );
  });

  it("says first when the model lost its held-out test", () => {
    const lost = { ...retrained, status: "rejected" } as ModelInfo;
    expect(promoteQuestion(lost, active, text)).toMatch(
      /^v2 did worse than the model it was compared with on the held-out scenes\. Warning: /,
    );
    expect(promoteQuestion(active, active, text)).not.toMatch(/active now|Warning/);
  });

  it("warns when the model was never judged on held-out scenes, not when a retrain compared it", () => {
    const shippedCandidate = model({
      id: "c",
      version: 2,
      status: "candidate",
      validation_accuracy: 0.99,
    });
    const judgedActive = { ...active, heldout_accuracy: 0.9, heldout_items: 40 } as ModelInfo;
    expect(promoteQuestion(shippedCandidate, judgedActive, text)).toMatch(
      /^Warning: v2 was never measured on held-out scenes of this team's labels; its figures below are not from the same scenes as the active model's\. Make v2/,
    );
    // Neither was: the figures do not compare the two at all.
    expect(promoteQuestion(shippedCandidate, active, text)).toMatch(
      /^Warning: neither v2 nor the active v1 was measured on held-out scenes of this team's labels: the figures below do not say which does better on them\. Make v2/,
    );
    // Rolled back to: the newest retrain from it compared the two on its held-out scenes.
    const retrainedFromIt = model({
      id: "d",
      version: 3,
      active: true,
      heldout_accuracy: 0.9,
      parent_id: "c",
      parent_version: 2,
      parent_heldout_accuracy: 0.95,
    });
    const others = [shippedCandidate, retrainedFromIt];
    expect(promoteQuestion(shippedCandidate, retrainedFromIt, text, others)).not.toMatch(
      /never measured/,
    );
  });

  it("warns when the held-out figure rests on a handful of items, not when it does not", () => {
    const close = { ...retrained, validation_accuracy: 0.98 } as ModelInfo;
    expect(promoteQuestion(close, active, text)).toMatch(/^Make v2 the active model\?/);
    const thin = { ...close, heldout_items: 1 } as ModelInfo;
    expect(promoteQuestion(thin, active, text)).toMatch(
      /^Its held-out figure rests on 1 item only: too few to tell two models apart\. Make v2/,
    );
  });
});

describe("the held-out column of a model never judged on held-out scenes of its own", () => {
  const text = KIND_TEXT.relation;
  const shipped = model({ id: "a", version: 1, active: true });
  const compared = (version: number, figure: number) =>
    model({
      id: `r${version}`,
      version,
      heldout_accuracy: 0.4,
      parent_id: "a",
      parent_version: 1,
      parent_heldout_accuracy: figure,
    });

  it("gives its figure from the newest comparison with a model retrained from it", () => {
    const others = [shipped, compared(2, 0.8), compared(3, 1.0)];
    expect(heldoutText(shipped, text, others)).toBe("100.0% on v3's held-out scenes");
    expect(promoteQuestion(compared(2, 0.8), shipped, text, others)).toContain(
      "v1 (active now): held-out accuracy 100.0% on v3's held-out scenes",
    );
  });

  it("says nothing it does not know", () => {
    expect(heldoutText(shipped, text, [shipped])).toBe("—");
  });

  it("gives a detector that is neither active nor a parent the figures a retrain measured", () => {
    const detector = KIND_TEXT.detector;
    const idle = model({ id: "c", version: 2, status: "default" });
    const retrain = model({
      id: "r4",
      version: 4,
      heldout_accuracy: 0.2,
      parent_id: "a",
      parent_heldout_accuracy: 0.1,
      heldout_items: 9,
      heldout_others: [{ model_id: "c", accuracy: 0.25, recall: 0.5 }],
    });
    const others = [shipped, idle, retrain];
    expect(heldoutText(idle, detector, others)).toBe(
      "25.0% · 50.0% on v4's held-out scenes (9 confirmed boxes)",
    );
    // Measured, so "Make active" no longer warns that it never was.
    expect(promoteQuestion(idle, shipped, detector, others)).not.toContain("Warning");
    expect(promoteQuestion(idle, shipped, detector, [shipped, idle])).toContain(
      "Warning: neither v2 nor the active v1 was measured",
    );
  });
});

describe("what the retrain form says about the labelled scenes", () => {
  const what = "scenes with supports set by a person";
  const counted = (labelled: number, heldout: number, other: string | null = null) => ({
    labelled_scenes: labelled,
    heldout_scenes: heldout,
    needed: 2,
    what,
    other_retrain: other,
  });

  it("counts them, and says how many are needed when they are too few", () => {
    expect(readinessText(counted(1, 0))).toBe(
      "1 labelled scene (scenes with supports set by a person): at least 2 are needed, " +
        "one to learn from and one to judge by.",
    );
    expect(readinessText(counted(3, 0))).toMatch(
      /: all of one photo, .*label a scene of another photo\.$/,
    );
    expect(readinessText(counted(2, 1))).toMatch(
      /^2 labelled scenes \(.*\): 1 of them is held out to judge the new model/,
    );
    expect(readinessText(counted(12, 3))).toMatch(/: 3 of them are held out/);
  });

  it("says which retrain of another kind this one waits for", () => {
    const other = "a retrain of the Relation Network started by adam (40%)";
    expect(readinessText(counted(2, 1, other))).toMatch(
      /held out to judge the new model, never trained on\. Waiting: a retrain of the Relation Network started by adam \(40%\) is running, and one retrain runs at a time\.$/,
    );
  });
});
