// The object editor's bookkeeping against a server that keeps every revision (as the real one
// does): each action is one revision, undo and redo restore the revision before or after it,
// a new action forgets what was undone, a failed action is kept until retried or dropped; and
// how an action is re-applied on a newer revision after a conflict.
import type { RevisionInfo, SceneDocument, SceneObject } from "@holiscene/schema";
import { beforeEach, describe, expect, it, vi } from "vitest";
import { api } from "../api/client";
import { ApiError } from "../api/errors";
import { MemoryStorage } from "../testing/memoryStorage";
import { sceneDocument, sceneObject, sessionOn } from "../testing/sceneDocuments";
import { revertTo } from "../views/scene/history/revertRevision";
import { DraftStore } from "./draftStore";
import { twinNote, uncutNote } from "./newObjectNotes";
import {
  type NewObject,
  type ObjectEdit,
  ObjectEditor,
  rebaseEdits,
  restoreEdits,
  savedAlready,
  touchedIds,
  WHOLE_SCENE,
} from "./objectEditor";
import type { SceneSession } from "./sceneSession";

const object = (id: string, cls = "chair") => sceneObject(id, cls);
const documentOf = (revision: number, objects: SceneObject[]) =>
  sceneDocument(objects, [], { revision });

/** Keeps every revision; applies object edits as the API does (objects only). */
class RevisionServer {
  readonly revisions: SceneDocument[];
  readonly requests: { base: number; edits: ObjectEdit[] }[] = [];
  refuseNext: string | null = null;
  /** Requests still to fail as an unreachable server's do (no answer at all). */
  unreachableFor = 0;

  constructor(first: SceneDocument) {
    this.revisions = [first];
  }

  get latest(): SceneDocument {
    return this.revisions.at(-1) as SceneDocument;
  }

  post = async (_scene: string, base: number, _author: string, edits: ObjectEdit[]) => {
    this.requests.push({ base, edits });
    if (this.unreachableFor > 0) {
      this.unreachableFor--;
      throw new TypeError("Failed to fetch");
    }
    if (this.refuseNext) {
      const reason = this.refuseNext;
      this.refuseNext = null;
      throw new ApiError(422, reason, "422");
    }
    let objects = [...(this.latest.scene.objects ?? [])];
    for (const edit of edits) {
      if (edit.kind === "restore_scene") {
        const then = this.revisions.find((r) => r.revision === edit.from_revision);
        if (!then) throw new ApiError(422, "no such revision", "422");
        objects = [...(then.scene.objects ?? [])];
      } else if (edit.kind === "add_object") objects.push(object(edit.id, edit.class));
      else if (edit.kind === "remove_object") objects = objects.filter((o) => o.id !== edit.id);
      else if (edit.kind === "set_class")
        objects = objects.map((o) => (o.id === edit.id ? object(o.id, edit.class) : o));
      else if (edit.kind === "restore_object") {
        const then = this.revisions.find((r) => r.revision === edit.from_revision);
        const old = then?.scene.objects?.find((o) => o.id === edit.id);
        objects = objects.filter((o) => o.id !== edit.id);
        if (old) objects.push(old);
      }
    }
    const doc = documentOf(this.latest.revision + 1, objects);
    this.revisions.push(doc);
    return doc;
  };
}

/** A new object drawn with the box tool. */
const drawn = (id: string, cls: string): NewObject => ({
  kind: "add_object",
  id,
  class: cls,
  bbox: [1, 1, 9, 9],
  source: "manual",
});

const classes = (session: SceneSession) =>
  Object.fromEntries(session.objects.map((o) => [o.id, o.class]));

describe("ObjectEditor", () => {
  let server: RevisionServer;
  let session: SceneSession;
  let editor: ObjectEditor;
  beforeEach(() => {
    server = new RevisionServer(documentOf(1, [object("o1", "chair")]));
    session = sessionOn(server.latest);
    editor = new ObjectEditor(session, { author: () => "tester", post: server.post });
  });

  it("saves each action as one revision on the loaded one, and adopts the answer", async () => {
    expect(
      await editor.apply(
        [{ kind: "add_object", id: "d1", class: "bed", bbox: [1, 1, 9, 9], source: "manual" }],
        "add bed d1",
      ),
    ).toBe(true);
    expect(await editor.apply([{ kind: "set_class", id: "o1", class: "sofa" }], "o1 → sofa")).toBe(
      true,
    );
    expect(server.requests.map((r) => r.base)).toEqual([1, 2]);
    expect(session.doc.revision).toBe(3);
    expect(classes(session)).toEqual({ o1: "sofa", d1: "bed" });
    expect(editor.undoLabel).toBe("o1 → sofa");
    expect(editor.status).toMatchObject({
      kind: "idle",
      message: "O1 → sofa: saved.",
    });
  });

  it("undo restores the revision before the action, redo the one it made, exactly", async () => {
    await editor.apply([{ kind: "set_class", id: "o1", class: "sofa" }], "o1 → sofa");
    await editor.apply([{ kind: "remove_object", id: "o1" }], "remove o1");
    expect(classes(session)).toEqual({});

    expect(await editor.undo()).toBe("remove o1");
    expect(server.requests.at(-1)?.edits).toEqual(restoreEdits(["o1"], 2));
    expect(classes(session)).toEqual({ o1: "sofa" });
    expect(await editor.undo()).toBe("o1 → sofa");
    expect(classes(session)).toEqual({ o1: "chair" });
    expect(editor.undoLabel).toBeNull();
    expect(await editor.undo()).toBeNull();

    expect(await editor.redo()).toBe("o1 → sofa");
    expect(server.requests.at(-1)?.edits).toEqual(restoreEdits(["o1"], 2));
    expect(classes(session)).toEqual({ o1: "sofa" });
    expect(editor.redoLabel).toBe("remove o1");
    // A new action forgets what was undone.
    await editor.apply([{ kind: "set_class", id: "o1", class: "desk" }], "o1 → desk");
    expect(editor.redoLabel).toBeNull();
    expect(editor.undoLabel).toBe("o1 → desk");
  });

  it("a revert restores the whole scene as one action, and its undo the revision before it", async () => {
    await editor.apply([{ kind: "set_class", id: "o1", class: "sofa" }], "o1 → sofa");
    await editor.apply([drawn("d1", "lamp")], "add lamp d1");
    await revertTo(editor, 1, server.revisions[0] as SceneDocument);
    expect(server.requests.at(-1)).toEqual({
      base: 3,
      edits: [{ kind: "restore_scene", from_revision: 1 }],
    });
    expect(classes(session)).toEqual({ o1: "chair" });
    expect(editor.undoLabel).toBe("revert to revision 1");

    expect(await editor.undo()).toBe("revert to revision 1");
    expect(server.requests.at(-1)?.edits).toEqual([{ kind: "restore_scene", from_revision: 3 }]);
    expect(classes(session)).toEqual({ o1: "sofa", d1: "lamp" });
    expect(await editor.redo()).toBe("revert to revision 1");
    expect(classes(session)).toEqual({ o1: "chair" });

    // Nothing to do: said, not sent.
    const sent = server.requests.length;
    expect(await revertTo(editor, 4, server.revisions[3] as SceneDocument)).toBe(
      "The scene is already as in revision 4.",
    );
    expect(server.requests.length).toBe(sent);
  });

  it("a revert waits for unsaved support edits to be saved or discarded", async () => {
    await editor.apply([{ kind: "set_class", id: "o1", class: "sofa" }], "o1 → sofa");
    session.edit("o1 on the floor", [
      { kind: "set_support", child: "o1", parent: "floor", type: "below" },
    ]);
    const sent = server.requests.length;
    expect(await revertTo(editor, 1, server.revisions[0] as SceneDocument)).toContain(
      "Save or discard your 1 unsaved change first",
    );
    expect(server.requests.length).toBe(sent);
    expect(session.unsavedCount).toBe(1); // still there
  });

  it("an undo of a revert is refused when anything in the scene changed since", async () => {
    await editor.apply([{ kind: "set_class", id: "o1", class: "sofa" }], "o1 → sofa");
    await revertTo(editor, 1, server.revisions[0] as SceneDocument);
    await server.post("s1", 3, "colleague", [drawn("d9", "lamp")]);
    session.adopt(server.latest);
    const posted = server.requests.length;
    expect(await editor.undo()).toBeNull();
    expect(server.requests.length).toBe(posted);
    expect(JSON.stringify(editor.status)).toContain("changed the scene since");
    expect(touchedIds([{ kind: "restore_scene", from_revision: 1 }])).toEqual([WHOLE_SCENE]);
    expect(restoreEdits([WHOLE_SCENE], 2)).toEqual([{ kind: "restore_scene", from_revision: 2 }]);
  });

  it("actions made quickly run one after another, each on the revision before it", async () => {
    const results = await Promise.all([
      editor.apply([{ kind: "set_class", id: "o1", class: "sofa" }], "a"),
      editor.apply([{ kind: "set_class", id: "o1", class: "desk" }], "b"),
      editor.undo(),
    ]);
    expect(results).toEqual([true, true, "b"]);
    expect(server.requests.map((r) => r.base)).toEqual([1, 2, 3]);
    expect(classes(session)).toEqual({ o1: "sofa" });
    expect(editor.busy).toBe(false);
  });

  it("two new objects made quickly get two ids; a retried one whose id was taken, a free one", async () => {
    const [first] = editor.newObjectIds(1);
    const adding = editor.apply(
      [{ kind: "add_object", id: first ?? "", class: "bed", bbox: [1, 1, 9, 9], source: "manual" }],
      "add bed",
    );
    const [second] = editor.newObjectIds(1);
    expect([first, second]).toEqual(["d1", "d2"]);
    await adding;
    expect(editor.newObjectIds(1)).toEqual(["d2"]); // d1 is in the scene now, d2 free again

    server.refuseNext = "down";
    const lamp = drawn("d2", "lamp");
    await editor.apply([lamp], "add lamp");
    await editor.apply([{ ...lamp, id: "d2", class: "desk" }], "add desk"); // took d2
    await editor.retry();
    expect(classes(session)).toEqual({ o1: "chair", d1: "bed", d2: "desk", d3: "lamp" });
  });

  it("a second action that fails while one is kept joins it: Retry saves both, in order", async () => {
    await editor.apply([{ kind: "set_class", id: "o1", class: "sofa" }], "o1 → sofa");
    server.refuseNext = "down";
    await editor.apply([{ kind: "set_class", id: "o1", class: "mirror" }], "o1 → mirror");
    server.refuseNext = "down";
    await editor.apply([drawn("d1", "night_stand")], "add night stand d1");
    expect(editor.failure?.label).toBe("o1 → mirror, then add night stand d1");
    // A failed undo is no work of its own: it does not take their place.
    server.refuseNext = "down";
    expect(await editor.undo()).toBeNull(); // of "o1 → sofa": refused too
    expect(server.refuseNext).toBeNull();
    expect(editor.failure?.label).toBe("o1 → mirror, then add night stand d1");
    expect(await editor.retry()).toBe(true);
    expect(classes(session)).toEqual({ o1: "mirror", d1: "night_stand" });
    expect(editor.failure).toBeNull();
  });

  it("an undo does not throw away what someone changed in the object since", async () => {
    await editor.apply([{ kind: "set_class", id: "o1", class: "sofa" }], "o1 → sofa");
    // A colleague makes o1 a desk; this page loads their revision.
    await server.post("s1", 2, "colleague", [{ kind: "set_class", id: "o1", class: "desk" }]);
    session.adopt(server.latest);
    const posted = server.requests.length;
    expect(await editor.undo()).toBeNull();
    expect(server.requests.length).toBe(posted);
    expect(classes(session)).toEqual({ o1: "desk" });
    expect(editor.status).toMatchObject({ kind: "idle", error: true });
    expect(JSON.stringify(editor.status)).toContain("changed o1 since");
    expect(editor.undoLabel).toBe("o1 → sofa"); // still there, for when it is safe again
  });

  it("an action that got no answer is sent again by itself until it is saved", async () => {
    editor = new ObjectEditor(session, { author: () => "tester", post: server.post, retryMs: 5 });
    server.unreachableFor = 2;
    expect(await editor.apply([{ kind: "set_class", id: "o1", class: "sofa" }], "o1 → sofa")).toBe(
      false,
    );
    expect(editor.failure).toMatchObject({ label: "o1 → sofa", retrying: true });
    expect(editor.failure?.message).toContain("could not be reached");
    await vi.waitFor(() => expect(editor.failure).toBeNull());
    expect(server.requests).toHaveLength(3);
    expect(classes(session)).toEqual({ o1: "sofa" });
    expect(session.drafts.loadFailedAction(session.sceneId)).toBeNull();
    expect(server.revisions).toHaveLength(2); // saved once
  });

  it("a refused action is not sent again by itself, and leaving the page stops the retries", async () => {
    editor = new ObjectEditor(session, { author: () => "tester", post: server.post, retryMs: 5 });
    server.refuseNext = "unknown class";
    await editor.apply([{ kind: "set_class", id: "o1", class: "sofaa" }], "o1 → sofaa");
    expect(editor.failure?.retrying).toBeUndefined();
    server.unreachableFor = 100;
    await editor.apply([{ kind: "set_class", id: "o1", class: "desk" }], "o1 → desk");
    editor.dispose();
    const sent = server.requests.length;
    await new Promise((resolve) => setTimeout(resolve, 30));
    expect(server.requests.length).toBe(sent);
    expect(editor.failure?.label).toBe("o1 → sofaa, then o1 → desk"); // still kept
  });

  it("a refused action is kept with its reason until retried (then saved once) or dropped", async () => {
    server.refuseNext = "unknown class 'sofaa'";
    expect(await editor.apply([{ kind: "set_class", id: "o1", class: "sofa" }], "o1 → sofa")).toBe(
      false,
    );
    expect(editor.failure).toEqual({ label: "o1 → sofa", message: "unknown class 'sofaa'" });
    expect(editor.undoLabel).toBeNull();
    expect(session.doc.revision).toBe(1);

    await editor.retry();
    expect(editor.failure).toBeNull();
    expect(classes(session)).toEqual({ o1: "sofa" });
    expect(editor.undoLabel).toBe("o1 → sofa");

    server.refuseNext = "no";
    await editor.apply([{ kind: "remove_object", id: "o1" }], "remove o1");
    editor.discardFailed();
    expect(editor.failure).toBeNull();
    expect(editor.status).toMatchObject({ message: "Dropped: remove o1." });
    expect(classes(session)).toEqual({ o1: "sofa" });
  });

  it("shows what an action does before the server answers, and takes it back if refused", async () => {
    let answer: () => void = () => {};
    const slow: typeof server.post = (...args) =>
      new Promise((resolve, reject) => {
        answer = () => server.post(...args).then(resolve, reject);
      });
    editor = new ObjectEditor(session, { author: () => "tester", post: slow });
    const saved = editor.apply([{ kind: "remove_object", id: "o1" }], "remove o1");
    await Promise.resolve();
    await new Promise((resolve) => setTimeout(resolve, 0));
    expect(classes(session)).toEqual({}); // at once, still on revision 1
    expect(session.doc.revision).toBe(1);
    answer();
    expect(await saved).toBe(true);
    expect(session.doc.revision).toBe(2);

    // The undo shows the object again at once too (revision 1 was seen here).
    const undone = editor.undo();
    await new Promise((resolve) => setTimeout(resolve, 0));
    expect(classes(session)).toEqual({ o1: "chair" });
    server.refuseNext = "down";
    answer();
    expect(await undone).toBeNull();
    expect(classes(session)).toEqual({}); // refused: back to what the server has
    expect(editor.failure?.label).toBe("undo remove o1");
  });

  it("an undo (or redo) the server refuses stays the one to undo (or redo)", async () => {
    await editor.apply([{ kind: "set_class", id: "o1", class: "sofa" }], "o1 → sofa");
    server.refuseNext = "down";
    expect(await editor.undo()).toBeNull();
    expect(editor.undoLabel).toBe("o1 → sofa");
    expect(editor.redoLabel).toBeNull();
    expect(editor.failure?.label).toBe("undo o1 → sofa");
    await editor.retry();
    expect(classes(session)).toEqual({ o1: "chair" });
    expect(editor.redoLabel).toBe("o1 → sofa");

    server.refuseNext = "down";
    expect(await editor.redo()).toBeNull();
    expect(editor.redoLabel).toBe("o1 → sofa");
    expect(editor.undoLabel).toBeNull();
    expect(editor.failure?.label).toBe("redo o1 → sofa");
    expect(await editor.retry()).toBe(true);
    expect(classes(session)).toEqual({ o1: "sofa" });
    expect(editor.undoLabel).toBe("o1 → sofa");
  });
});

describe("a failed object action outlives the page", () => {
  let storage: MemoryStorage;
  let server: RevisionServer;
  /** A visit: a new page on the latest revision, with the same localStorage. */
  const visit = () =>
    new ObjectEditor(sessionOn(server.latest, storage), {
      author: () => "tester",
      post: server.post,
    });
  const kept = () => new DraftStore(storage).loadFailedAction("s1");
  beforeEach(() => {
    storage = new MemoryStorage();
    server = new RevisionServer(documentOf(1, [object("o1", "chair")]));
  });

  it("is offered again on the next visit, kept while a retry fails, forgotten once saved", async () => {
    server.refuseNext = "server down";
    await visit().apply([{ kind: "set_class", id: "o1", class: "sofa" }], "o1 → sofa");

    const next = visit(); // the tab was closed
    expect(next.failure?.label).toBe("o1 → sofa");
    // Said as then: the server may answer now.
    expect(next.failure?.message).toMatch(
      /^Not saved on your last visit \(.+\): server down\. Retry sends it now\.$/,
    );
    server.refuseNext = "still down";
    expect(await next.retry()).toBe(false);
    expect(kept()).toMatchObject({ label: "o1 → sofa", message: "still down" });
    expect(await next.retry()).toBe(true);
    expect(classes(next.session)).toEqual({ o1: "sofa" });
    expect(next.failure).toBeNull();
    expect(kept()).toBeNull();
    expect(visit().failure).toBeNull();
  });

  it("a failed undo is kept as its restore edits; a dropped action is forgotten", async () => {
    const editor = visit();
    await editor.apply([{ kind: "set_class", id: "o1", class: "sofa" }], "o1 → sofa");
    server.refuseNext = "server down";
    await editor.undo();
    expect(kept()).toMatchObject({ label: "undo o1 → sofa", edits: restoreEdits(["o1"], 1) });

    const next = visit();
    expect(next.failure?.label).toBe("undo o1 → sofa");
    next.discardFailed();
    expect(kept()).toBeNull();
    expect(visit().failure).toBeNull();
    expect(server.latest.scene.objects?.[0]?.class).toBe("sofa");
  });

  it("a retry says first when someone else changed its object since, then puts it on top", async () => {
    server.refuseNext = "server down";
    await visit().apply([{ kind: "set_class", id: "o1", class: "sofa" }], "o1 → sofa");
    // Bob makes o1 a table; the next visit loads his revision.
    await server.post("s1", 1, "bob", [{ kind: "set_class", id: "o1", class: "table" }]);
    const listRevisions = vi
      .spyOn(api, "listRevisions")
      .mockResolvedValue([{ number: 2, author: "bob" }] as RevisionInfo[]);
    const getRevision = vi
      .spyOn(api, "getRevision")
      .mockResolvedValue(server.revisions[0] as SceneDocument);
    try {
      const next = visit();
      const sent = server.requests.length;
      expect(await next.retry()).toBe(false);
      expect(server.requests.length).toBe(sent); // nothing sent over Bob's table
      expect(next.failure?.message).toBe(
        "bob changed o1 since you made this change. Retry again to put yours on top of " +
          "theirs, or Discard to keep theirs.",
      );
      expect(classes(next.session)).toEqual({ o1: "table" });
      expect(await next.retry()).toBe(true);
      expect(classes(next.session)).toEqual({ o1: "sofa" });
      expect(kept()).toBeNull();
    } finally {
      listRevisions.mockRestore();
      getRevision.mockRestore();
    }
  });

  it("a stored action that is not one is ignored", () => {
    storage.setItem("holiscene.draft.s1.failedObjectAction", '{"label":"x","edits":[]}');
    expect(visit().failure).toBeNull();
  });
});

describe("rebaseEdits", () => {
  it("gives a new object whose id was taken meanwhile a free one, and its later edits follow", () => {
    const rebased = rebaseEdits(
      [
        { kind: "add_object", id: "d1", class: "bed", bbox: [0, 0, 5, 5], source: "manual" },
        { kind: "set_class", id: "d1", class: "sofa" },
      ],
      [object("d1"), object("d2")],
    );
    expect(rebased).toEqual({
      edits: [
        { kind: "add_object", id: "d3", class: "bed", bbox: [0, 0, 5, 5], source: "manual" },
        { kind: "set_class", id: "d3", class: "sofa" },
      ],
      renamed: [["d1", "d3"]],
    });
  });

  it("cannot apply a change to an object that is gone; a restore always applies", () => {
    expect(
      rebaseEdits(
        [
          { kind: "set_class", id: "o9", class: "sofa" },
          { kind: "remove_object", id: "o1" },
        ],
        [object("o1")],
      ),
    ).toEqual({ edits: null, missing: ["o9"] });
    const restore = restoreEdits(["o9"], 4);
    expect(rebaseEdits(restore, [])).toEqual({ edits: restore, renamed: [] });
  });

  it("touchedIds names each object once", () => {
    expect(
      touchedIds([
        { kind: "set_class", id: "a", class: "bed" },
        { kind: "set_bbox", id: "a", bbox: [0, 0, 5, 5] },
        { kind: "remove_object", id: "b" },
      ]),
    ).toEqual(["a", "b"]);
  });
});

describe("an action whose answer was lost", () => {
  const added: ObjectEdit[] = [
    { kind: "add_object", id: "d1", class: "lamp", bbox: [1, 2, 30, 40], source: "manual" },
    { kind: "set_class", id: "o1", class: "sofa" },
  ];
  // As the server lists them: every field written out, defaults included, keys in its order.
  const stored = [
    { number: 4, edits: [{ kind: "set_class", id: "o1", class: "sofa" }] },
    {
      number: 5,
      edits: [
        {
          bbox: [1, 2, 30, 40],
          class: "lamp",
          id: "d1",
          kind: "add_object",
          mask: null,
          score: null,
          source: "manual",
        },
        { class: "sofa", id: "o1", kind: "set_class" },
      ],
    },
  ] as const;

  it("is found in the revisions saved since its base, whatever the server's field order", () => {
    expect(savedAlready(stored as never, 3, added)).toBe(5);
    expect(savedAlready(stored as never, 5, added)).toBeNull(); // not after its base
  });

  it("is not taken for another action with a different value or fewer edits", () => {
    expect(
      savedAlready(stored as never, 3, [
        { ...added[0], bbox: [1, 2, 30, 41] } as ObjectEdit,
        added[1] as ObjectEdit,
      ]),
    ).toBeNull();
    expect(savedAlready(stored as never, 3, added.slice(0, 1))).toBeNull();
    expect(savedAlready([{ number: 6, edits: null }] as never, 3, added)).toBeNull();
  });
});

describe("new objects the server could not cut out", () => {
  const withMask = (id: string, source: "box" | "grabcut"): SceneObject => ({
    ...object(id),
    mask: { origin: [0, 0], size: [4, 4], rle: [0, 16], source },
  });
  const add = (id: string): NewObject => ({
    kind: "add_object",
    id,
    class: "chair",
    bbox: [0, 0, 4, 4],
    source: "detector",
  });

  it("are named, with how to fix their masks", () => {
    const doc = documentOf(3, [withMask("d1", "box"), withMask("d2", "grabcut")]);
    expect(uncutNote([add("d1"), add("d2")], doc)).toBe(
      " But d1's mask is its whole box: fix with Brush, Eraser or Refine (the automatic cut " +
        "could not separate it).",
    );
    const both = documentOf(3, [withMask("d1", "box"), withMask("d2", "box")]);
    expect(uncutNote([add("d1"), add("d2")], both)).toMatch(/^ But the masks of d1, d2 are their/);
  });

  it("say nothing when every new object was cut, or its mask was given", () => {
    const doc = documentOf(3, [withMask("d1", "grabcut"), withMask("o1", "box")]);
    expect(uncutNote([add("d1"), { kind: "remove_object", id: "o2" }], doc)).toBe("");
    const given = {
      ...add("o1"),
      mask: { origin: [0, 0], size: [4, 4], rle: [0, 16], source: "box" },
    };
    expect(uncutNote([given as NewObject], doc)).toBe("");
  });
});

describe("new objects on top of one of their class", () => {
  const at = (id: string, cls: string, bbox: [number, number, number, number]): SceneObject => ({
    ...object(id, cls),
    bbox,
  });
  const add = (id: string): NewObject => ({
    kind: "add_object",
    id,
    class: "bed",
    bbox: [0, 0, 4, 4],
    source: "detector",
  });

  it("are named with the object they overlap, and how to undo the twin", () => {
    const doc = documentOf(7, [
      at("o0", "bed", [10, 50, 200, 180]),
      at("d3", "bed", [0, 20, 190, 170]),
    ]);
    expect(twinNote([add("d3")], doc)).toBe(
      " d3 overlaps o0, also a bed: if they are the same bed, select d3 and remove it (Delete).",
    );
    // Inside a larger box of its class: a part taken for a second one.
    const inside = documentOf(7, [
      at("o0", "bed", [0, 0, 400, 300]),
      at("d3", "bed", [10, 10, 60, 40]),
    ]);
    expect(twinNote([add("d3")], inside)).toMatch(/^ d3 overlaps o0/);
  });

  it("say nothing of other classes, boxes apart, or objects added together", () => {
    const otherClass = documentOf(7, [
      at("o0", "sofa", [10, 50, 200, 180]),
      at("d3", "bed", [0, 20, 190, 170]),
    ]);
    expect(twinNote([add("d3")], otherClass)).toBe("");
    const apart = documentOf(7, [
      at("o0", "bed", [0, 0, 100, 100]),
      at("d3", "bed", [80, 0, 180, 100]),
    ]);
    expect(twinNote([add("d3")], apart)).toBe("");
    const together = documentOf(7, [
      at("d2", "bed", [0, 0, 100, 100]),
      at("d3", "bed", [0, 0, 100, 100]),
    ]);
    expect(twinNote([add("d2"), add("d3")], together)).toBe("");
  });
});
