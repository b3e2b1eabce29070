// Live suggestions on a real session: a correction that makes another object's guess close a
// loop turns that guess into the model's next answer; accepting or rejecting follows.
import type { SupportRelation } from "@holiscene/schema";
import { describe, expect, it } from "vitest";
import {
  acceptAll,
  acceptEdge,
  rejectEdge,
  removeSupport,
  setSupporter,
} from "../editors/supportActions";
import type { SceneSession } from "../state/sceneSession";
import { sceneDocument, sceneObject, sessionOn } from "../testing/sceneDocuments";
import { makeSuggester } from "./suggester";

// Columns: o0, o1, o2, ceiling, floor, wall; types below, behind.
function table(rows: Record<string, number>[]): number[] {
  const columns = ["o0", "o1", "o2", "ceiling", "floor", "wall"];
  return rows.flatMap((row) =>
    columns.flatMap((c) => [row[`${c} below`] ?? 0.001, row[`${c} behind`] ?? 0.001]),
  );
}

// o0: on the floor (sure); o1: on o2 (0.6) else on o0 (0.3); o2: on o1 (0.5) else floor (0.4).
const probabilities = table([
  { "floor below": 0.95 },
  { "o2 below": 0.6, "o0 below": 0.3 },
  { "o1 below": 0.5, "floor below": 0.4 },
]);

const auto = (child: string, parent: string): SupportRelation => ({
  child,
  parent,
  type: "below",
  source: "auto",
  confidence: 0.5,
  author: null,
  time: null,
});

function session(): SceneSession {
  const doc = sceneDocument(
    ["o0", "o1", "o2"].map((id) => sceneObject(id, "box", [0, 0, 1, 1])),
    // The pipeline's tree from the same table: o1 is surer, so o2 had to take the floor.
    [auto("o0", "floor"), auto("o1", "o2"), auto("o2", "floor")],
    { revision: 2, size: 10 },
  );
  doc.scene.stages = [
    { name: "supports_from_network", seconds: 0.1, note: null, warning: false, model: null },
  ];
  const s = sessionOn(doc, null);
  s.setSuggester(makeSuggester({ ids: ["o0", "o1", "o2"], probabilities }));
  return s;
}

describe("live suggestions", () => {
  it("agree with the pipeline before any correction", () => {
    expect(session().suggestions().size).toBe(0);
  });

  it("a correction moves another object's guess", () => {
    const s = session();
    // The annotator says o1 stands on o0: o2 is now free to rest on o1, its best answer.
    expect(setSupporter(s, "o1", "o0")).toBeNull();
    expect(s.suggestions().get("o2")).toMatchObject({ parent: "o1", type: "below" });
    expect(s.displayed("o2")).toMatchObject({ parent: "o1", suggested: true });
    // Undo: back to the pipeline's tree, no suggestion.
    s.undo();
    expect(s.suggestions().size).toBe(0);
  });

  it("accept takes the suggestion; accept-all takes every remaining edge as shown", () => {
    const s = session();
    setSupporter(s, "o1", "o0");
    acceptEdge(s, "o2");
    expect(s.shown().get("o2")).toMatchObject({ parent: "o1", source: "manual" });
    expect(s.suggestions().size).toBe(0);
    expect(acceptAll(s)).toBeNull();
    expect(s.pending.map((e) => e.child).sort()).toEqual(["o0", "o1", "o2"]);
    expect(acceptAll(s)).toBe("Nothing left to accept.");
  });

  it("rejecting a guess shows the model's next answer", () => {
    const s = session();
    rejectEdge(s, "o1"); // not on o2
    expect(s.shown().has("o1")).toBe(false);
    // o1's next answer is o0; o2 may now take o1 (no loop).
    expect(s.suggestions().get("o1")).toMatchObject({ parent: "o0" });
    expect(s.suggestions().get("o2")).toMatchObject({ parent: "o1" });
    rejectEdge(s, "o1"); // not on o0 either: the suggestion goes, the next one comes
    const next = s.suggestions().get("o1");
    expect(next).toBeDefined();
    expect([`${next?.parent} ${next?.type}`]).not.toContain("o0 below");
    expect([`${next?.parent} ${next?.type}`]).not.toContain("o2 below");
    expect(s.shown().has("o1")).toBe(false);
  });
});

describe("objects left without a supporter", () => {
  it("get no suggestion when removed, the next answer when rejected", () => {
    const s = session();
    s.edit("remove", [{ kind: "remove_support", child: "o1" }]);
    expect(s.suggestions().has("o1")).toBe(false);
    s.undo();
    rejectEdge(s, "o1");
    expect(s.suggestions().get("o1")?.parent).toBe("o0");
  });
});

describe("a scene no support stage has run on (imported without the pipeline)", () => {
  it("offers a supporter for every object without one, none for one a person set", () => {
    const s = session();
    s.adopt({ ...s.doc, revision: 3, scene: { ...s.doc.scene, stages: [], supports: [] } });
    expect([...s.suggestions().keys()].sort()).toEqual(["o0", "o1", "o2"]);
    expect(s.suggestions().get("o0")).toMatchObject({ parent: "floor", type: "below" });
    expect(setSupporter(s, "o0", "wall")).toBeNull();
    expect(s.suggestions().has("o0")).toBe(false);
    expect([...s.suggestions().keys()].sort()).toEqual(["o1", "o2"]);
  });
});

describe("a correction against a guess", () => {
  it("drops the guess that would close a loop, and the model suggests its next answer", () => {
    const s = session();
    // o1's guess is "on o2"; the annotator says o2 stands on o1.
    expect(setSupporter(s, "o2", "o1")).toBeNull();
    expect(s.shown().get("o2")).toMatchObject({ parent: "o1", source: "manual" });
    expect(s.shown().has("o1")).toBe(false);
    expect(s.displayed("o1")).toMatchObject({ parent: "o0", suggested: true });
    // One action: undo gives both back.
    s.undo();
    expect(s.shown().get("o1")).toMatchObject({ parent: "o2", source: "auto" });
    expect(s.shown().get("o2")).toMatchObject({ parent: "floor", source: "auto" });
  });

  it("is refused when people's edges make the loop", () => {
    const s = session();
    acceptEdge(s, "o1"); // o1 on o2, by a person now
    expect(setSupporter(s, "o2", "o1")).toBe("o1 rests on o2: pick another supporter.");
  });

  it("an object a person added gets the model's supporter; one whose supporter they removed does not", () => {
    const s = session();
    const added = s.objects.map((o) =>
      o.id === "o2" ? { ...o, set_by_person: ["object" as const] } : o,
    );
    s.adopt({
      ...s.doc,
      revision: 3,
      scene: {
        ...s.doc.scene,
        objects: added,
        supports: s.doc.scene.supports.filter((x) => x.child !== "o2"),
      },
    });
    // Its best answer in the tree decoded with the others: the floor.
    expect(s.suggestions().get("o2")).toMatchObject({ parent: "floor", type: "below" });
    // Once it has a saved supporter, removing it by hand is a decision: none is offered.
    s.adopt({
      ...s.doc,
      revision: 4,
      scene: { ...s.doc.scene, supports: [...s.doc.scene.supports, auto("o2", "floor")] },
    });
    expect(removeSupport(s, "o2")).toBeNull();
    expect(s.suggestions().has("o2")).toBe(false);
  });

  it("scores of an older revision (before the new one is scored) name no object that is gone", () => {
    const s = session();
    // o2 removed: the server dropped its support and o1's, which stood on it; o1 was added
    // by a person, so the model's answer for it (o2 first) would be offered.
    s.adopt({
      ...s.doc,
      revision: 3,
      scene: {
        ...s.doc.scene,
        objects: s.objects
          .filter((o) => o.id !== "o2")
          .map((o) => (o.id === "o1" ? { ...o, set_by_person: ["object" as const] } : o)),
        supports: s.doc.scene.supports.filter((x) => x.child === "o0"),
      },
    });
    const named = [...s.suggestions().values()].flatMap((x) => [x.child, x.parent]);
    expect(named).not.toContain("o2");
  });
});
