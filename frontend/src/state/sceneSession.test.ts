// The session's editing without a server: undo and redo across edits (a predicted edge comes
// back as predicted), discarding, rejected answers, and drafts that outlive the page.
import type { SupportRelation } from "@holiscene/schema";
import { beforeEach, describe, expect, it } from "vitest";
import { MemoryStorage } from "../testing/memoryStorage";
import { sceneDocument, sceneObject, sessionOn } from "../testing/sceneDocuments";
import { supportRelation } from "../testing/supports";
import { DraftStore } from "./draftStore";
import { plural, type SceneSession } from "./sceneSession";

const auto = (child: string, parent: string, confidence = 0.8): SupportRelation =>
  supportRelation(child, parent, { confidence });

/** Objects o0, o1, o2 side by side. */
const doc = (supports: SupportRelation[], revision = 2) =>
  sceneDocument(
    ["o0", "o1", "o2"].map((id, i) => sceneObject(id, "box", [i * 10, 0, i * 10 + 8, 8])),
    supports,
    { revision },
  );

describe("SceneSession editing", () => {
  let storage: MemoryStorage;
  let session: SceneSession;
  beforeEach(() => {
    storage = new MemoryStorage();
    session = sessionOn(doc([auto("o0", "floor"), auto("o1", "o0")]), storage);
  });

  it("accepting a guess makes it a person's label; undo gives the guess back as a guess", () => {
    session.edit("accept o1", [{ kind: "set_support", child: "o1", parent: "o0", type: "below" }]);
    expect(session.pending).toHaveLength(1);
    expect(session.shown().get("o1")).toMatchObject({ source: "manual", pending: true });
    expect(session.isResolved("o1")).toBe(true);

    expect(session.undo()).toBe("accept o1");
    expect(session.pending).toHaveLength(0);
    expect(session.shown().get("o1")).toMatchObject({ source: "auto", confidence: 0.8 });
    expect(session.saveState.kind).toBe("clean");

    expect(session.redo()).toBe("accept o1");
    expect(session.shown().get("o1")).toMatchObject({ source: "manual", pending: true });
    expect(session.redo()).toBeNull();
  });

  it("undoes several edits of one object one by one, and a new edit forgets the redo", () => {
    const set = (parent: string) =>
      session.edit(`o2 on ${parent}`, [
        { kind: "set_support", child: "o2", parent, type: "below" },
      ]);
    set("o0");
    set("o1");
    session.edit("flip", [{ kind: "set_support", child: "o2", parent: "o1", type: "behind" }]);
    expect(session.shown().get("o2")).toMatchObject({ parent: "o1", type: "behind" });
    session.undo();
    expect(session.shown().get("o2")).toMatchObject({ parent: "o1", type: "below" });
    session.undo();
    expect(session.shown().get("o2")).toMatchObject({ parent: "o0" });
    session.undo();
    expect(session.shown().has("o2")).toBe(false);
    expect(session.pending).toHaveLength(0);
    session.redo();
    set("floor");
    expect(session.redoLabel).toBeNull();
    expect(session.undoLabel).toBe("o2 on floor");
  });

  it("one action may change several objects and is undone as one", () => {
    session.edit("accept all", [
      { kind: "set_support", child: "o0", parent: "floor", type: "below" },
      { kind: "set_support", child: "o1", parent: "o0", type: "below" },
    ]);
    expect(session.pending).toHaveLength(2);
    session.undo();
    expect(session.pending).toHaveLength(0);
  });

  it("drops unsaved edits about an object a new revision removed, and says so", () => {
    session.edit("o2 on o1", [{ kind: "set_support", child: "o2", parent: "o1", type: "below" }]);
    session.edit("o1 on floor", [
      { kind: "set_support", child: "o1", parent: "floor", type: "below" },
    ]);
    session.edit("o0 on wall", [
      { kind: "set_support", child: "o0", parent: "wall", type: "behind" },
    ]);
    // The object editor removed o1: revision 3 comes back from the server without it.
    const without = sceneDocument(
      ["o0", "o2"].map((id, i) => sceneObject(id, "box", [i * 20, 0, i * 20 + 8, 8])),
      [auto("o0", "floor")],
      { revision: 3 },
    );
    session.adopt(without);
    // Only the edit the server can still take is left: saving is not refused for the others.
    expect(session.pending.map((e) => e.child)).toEqual(["o0"]);
    expect(session.notice).toContain('Dropped your unsaved edit "o2');
    expect(session.notice).toContain('"o1');
  });

  it("discarding is an action too", () => {
    session.edit("remove", [{ kind: "remove_support", child: "o1" }]);
    session.discard();
    expect(session.pending).toHaveLength(0);
    session.undo();
    expect(session.pending.map((e) => e.kind)).toEqual(["remove_support"]);
    // What Undo brought back after Discard waits for Save: an Undo meant for an earlier
    // action would otherwise store it unseen. The next edit, or Redo, lets autosave go on.
    expect(session.holdAutosave).toBe("undone discard");
    session.redo();
    expect(session.holdAutosave).toBeNull();
    session.undo();
    expect(session.holdAutosave).toBe("undone discard");
    session.edit("remove", [{ kind: "remove_support", child: "o2" }]);
    expect(session.holdAutosave).toBeNull();
  });

  it("remembers rejected answers with the edit, and undo forgets them", () => {
    session.edit(
      "reject",
      [{ kind: "remove_support", child: "o1" }],
      [{ child: "o1", parent: "o0", type: "below" }],
    );
    expect([...session.rejectedAnswers("o1")]).toEqual(["o0|below"]);
    session.undo();
    expect(session.rejectedAnswers("o1").size).toBe(0);
    expect(session.shown().get("o1")?.parent).toBe("o0");
  });

  it("the selected object is the object of the selected id (none for a structure or nothing)", () => {
    expect(session.selectedObject).toBeUndefined();
    session.select("o1");
    expect(session.selectedObject?.id).toBe("o1");
    session.select("floor");
    expect(session.selectedObject).toBeUndefined();
  });

  it("keeps unsaved edits in storage and offers them to the next visit", () => {
    session.edit("o2 on o1", [{ kind: "set_support", child: "o2", parent: "o1", type: "below" }]);
    session.edit("reject o1", [{ kind: "remove_support", child: "o1" }]);
    const stored = new DraftStore(storage).load("s1");
    expect(stored?.edits.map((e) => e.child)).toEqual(["o2", "o1"]);

    // The tab closes; a new visit finds them.
    const next = sessionOn(doc([auto("o0", "floor"), auto("o1", "o0")]), storage);
    expect(next.recovered?.edits).toHaveLength(2);
    expect(next.pending).toHaveLength(0);
    // Its own edits before deciding do not overwrite what is offered.
    next.edit("o0 on wall", [{ kind: "set_support", child: "o0", parent: "wall", type: "behind" }]);
    const third = sessionOn(doc([auto("o0", "floor"), auto("o1", "o0")]), storage);
    expect(third.recovered?.edits.map((e) => e.child).sort()).toEqual(["o0", "o1", "o2"]);
    third.restoreRecovered();
    expect(third.pending).toHaveLength(3);
    expect(third.recovered).toBeNull();
    expect(third.notice).toContain("Restored 3 unsaved changes");
    // Restoring is undoable.
    third.undo();
    expect(third.pending).toHaveLength(0);
    expect(new DraftStore(storage).load("s1")).toBeNull();
  });

  it("drops recovered edits that are already saved", () => {
    session.edit("o2 on o1", [{ kind: "set_support", child: "o2", parent: "o1", type: "below" }]);
    const manual: SupportRelation = {
      child: "o2",
      parent: "o1",
      type: "below",
      source: "manual",
      author: "ann",
      time: "2026-01-01T00:00:01Z",
      confidence: null,
    };
    const next = sessionOn(doc([auto("o0", "floor"), auto("o1", "o0"), manual], 3), storage);
    next.restoreRecovered();
    expect(next.pending).toHaveLength(0);
    expect(next.notice).toContain("already saved");
  });
});

describe("the model's suggestions", () => {
  it("replace a guess while the scene is editable, and never on a read-only scene", () => {
    const session = sessionOn(doc([auto("o0", "floor"), auto("o1", "o0")]), new MemoryStorage());
    const changes: string[] = [];
    session.subscribe((change) => changes.push(change));
    session.setSuggester(
      () => new Map([["o1", { child: "o1", parent: "wall", type: "behind", probability: 0.4 }]]),
    );
    expect(session.displayed("o1")).toMatchObject({ parent: "wall", suggested: true });

    // Submitted: a reviewer sees what is stored, not what the model would say next.
    session.setWorkflow({
      scene_id: "s",
      state: "submitted",
      assignee: "ann",
      annotation_round: 1,
      archived_by: null,
      events: [],
      review_comment: null,
      revision: 2,
      editable: false,
      editable_reason: "submitted: waiting for review",
    });
    expect(session.editable).toBe(false);
    expect(session.suggestions().size).toBe(0);
    expect(session.displayed("o1")).toMatchObject({ parent: "o0", suggested: false });
    expect(changes).toContain("suggestions"); // the arrows are drawn again
  });
});

describe("an armed supporter pick", () => {
  it("is spent by any support edit, as by a picked supporter", () => {
    const session = sessionOn(doc([auto("o0", "floor"), auto("o1", "o0")]), new MemoryStorage());
    session.select("o1");
    session.setPicking("o1");
    session.edit("o1 on floor", [
      { kind: "set_support", child: "o1", parent: "floor", type: "below" },
    ]);
    expect(session.picking).toBeNull();
    expect(session.selected).toBe("o1");
  });
});

describe("plural", () => {
  it("counts nouns, with -es where English wants it", () => {
    expect(plural(1, "box")).toBe("1 box");
    expect(plural(2, "box")).toBe("2 boxes");
    expect(plural(0, "object")).toBe("0 objects");
    expect(plural(3, "unsaved change")).toBe("3 unsaved changes");
    expect(plural(2, "class")).toBe("2 classes");
  });
});
