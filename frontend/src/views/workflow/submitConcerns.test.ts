// Before a submit: objects without a supporter, suggestions nobody accepted, and people's
// labels the model doubts are named.
import type { SceneObject } from "@holiscene/schema";
import { describe, expect, it } from "vitest";
import type { DisplayedSupport, SceneSession } from "../../state/sceneSession";
import type { ShownSupport } from "../../state/supportGraph";
import { unsettledSupports } from "./submitConcerns";

const object = (id: string) => ({ id, class: "books", bbox: [0, 0, 10, 10] }) as SceneObject;
const stored = (child: string, parent: string) =>
  ({ child, parent, type: "below", source: "auto", pending: false }) as unknown as ShownSupport;

function session(shown: ShownSupport[], suggestedFor: string[], doubted: string[] = []) {
  const byChild = new Map(shown.map((s) => [s.child, s]));
  return {
    objects: ["o1", "o2", "o3"].map(object),
    shown: () => byChild,
    doubtedLabels: () => new Set(doubted),
    displayed: (child: string) =>
      ({ child, suggested: suggestedFor.includes(child) }) as unknown as DisplayedSupport,
  } as unknown as SceneSession;
}

describe("unsettledSupports", () => {
  it("names objects without a supporter and suggestions nobody accepted", () => {
    const concerns = unsettledSupports(session([stored("o1", "floor")], ["o1", "o2"]));
    expect(concerns).toEqual([
      "2 objects (o2, o3) have no supporter.",
      "2 objects (o1, o2) have a supporter the model suggests and nobody accepted (dashed in " +
        "the list): the stored one is what is submitted.",
    ]);
  });

  it("names people's labels the model is sure are something else", () => {
    const all = ["o1", "o2", "o3"].map((id) => stored(id, "floor"));
    expect(unsettledSupports(session(all, [], ["o3"]))).toEqual([
      "1 object (o3) has a supporter set by a person that the support model is sure is " +
        "something else (orange in the list): worth a second look.",
    ]);
  });

  it("says nothing when every support is stored and no suggestion waits", () => {
    const all = ["o1", "o2", "o3"].map((id) => stored(id, "floor"));
    expect(unsettledSupports(session(all, []))).toEqual([]);
  });
});
