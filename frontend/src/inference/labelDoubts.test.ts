import { describe, expect, it } from "vitest";
import type { ShownSupport } from "../state/supportGraph";
import { doubtedLabels } from "./labelDoubts";
import type { SceneScores, SupportSuggestion } from "./supportModel";

function label(child: string, parent: string, type: "below" | "behind", manual = true) {
  const shown: ShownSupport = {
    child,
    parent,
    type,
    saved: null,
    pending: false,
    source: manual ? "manual" : "auto",
    author: manual ? "anna" : null,
    time: null,
    confidence: null,
  };
  return [child, shown] as const;
}

function scores(best: Record<string, SupportSuggestion>): SceneScores {
  return {
    ids: Object.keys(best),
    classes: [],
    priors: null,
    probabilities: new Float64Array(),
    ranked: Object.entries(best).map(([id, answer]) => ({
      id,
      ranked: [answer, { supporter: "wall", type: "behind", probability: 0.01 }],
    })),
  };
}

describe("labels the support model doubts", () => {
  const model = scores({
    o1: { supporter: "o7", type: "below", probability: 0.99 },
    o2: { supporter: "floor", type: "below", probability: 0.95 },
    o3: { supporter: "o1", type: "below", probability: 0.6 },
    o4: { supporter: "floor", type: "below", probability: 0.9 },
  });

  it("flags a person's label only where a confident model says otherwise", () => {
    const shown = new Map([
      label("o1", "ceiling", "behind"), // contradicts a 99% answer: flagged
      label("o2", "floor", "below"), // agrees
      label("o3", "floor", "below"), // the model is unsure (60%)
      label("o4", "wall", "behind", false), // the pipeline's guess, not a person's label
    ]);
    const doubted = doubtedLabels(shown, model);
    expect([...doubted.keys()]).toEqual(["o1"]);
    expect(doubted.get("o1")).toEqual({ supporter: "o7", type: "below", probability: 0.99 });
  });

  it("counts the type as part of the answer, and says nothing without scores", () => {
    const shown = new Map([label("o2", "floor", "behind")]);
    expect([...doubtedLabels(shown, model).keys()]).toEqual(["o2"]);
    expect(doubtedLabels(shown, null).size).toBe(0);
  });
});
