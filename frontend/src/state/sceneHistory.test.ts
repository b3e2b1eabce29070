// The session with the room layout attached: one undo history across support edits and corner
// drags, in order; the corners saved with the support edits and kept in the draft in
// localStorage; an undo after a save saved as a change back; read-only scenes (submitted,
// accepted, the server's word, a refused save) that keep the user's unsaved work.
import type { EditRequest, SceneDocument, SceneWorkflow } from "@holiscene/schema";
import { afterEach, beforeEach, describe, expect, it, vi } from "vitest";
import { api } from "../api/client";
import { ConflictError } from "../api/errors";
import type { Point2 } from "../geometry/camera";
import { projectRoomCorners } from "../geometry/roomFit";
import { MemoryStorage } from "../testing/memoryStorage";
import { documentFor, inPhoto, manualFrames, ROOM } from "../testing/roomScene";
import { supportRelation } from "../testing/supports";
import { DraftStore } from "./draftStore";
import { LayoutDraft } from "./layoutDraft";
import { SceneSession } from "./sceneSession";

const scene = (revision = 3) =>
  documentFor(
    ROOM,
    {
      objects: [
        { id: "o0", class: "bed", bbox: [100, 300, 300, 420] },
        { id: "o1", class: "pillow", bbox: [120, 300, 160, 330] },
      ] as SceneDocument["scene"]["objects"],
      supports: [supportRelation("o0", "floor"), supportRelation("o1", "o0")],
    },
    revision,
  );

function workflow(
  state: SceneWorkflow["state"],
  permission: { editable?: boolean; editable_reason?: string | null } = {},
): SceneWorkflow {
  return {
    scene_id: "s",
    state,
    assignee: "ann",
    annotation_round: 1,
    archived_by: null,
    events: [],
    review_comment: null,
    revision: 3,
    ...permission,
  } as SceneWorkflow;
}

/** What the server stores for a request: the edits applied, the layout as the draft fitted it. */
function stored(base: SceneDocument, draft: LayoutDraft, body: EditRequest): SceneDocument {
  const supports = new Map((base.scene.supports ?? []).map((s) => [s.child, s]));
  let layout = base.scene.layout;
  let camera = base.scene.camera;
  for (const edit of body.edits) {
    if (edit.kind === "set_support") {
      supports.set(edit.child, {
        ...edit,
        source: "manual",
        confidence: null,
        author: "ann",
        time: null,
      });
    } else if (edit.kind === "set_layout" && draft.live && camera) {
      const { pitchDeg, rollDeg, corners3d } = draft.live;
      camera = { ...camera, pitch_deg: pitchDeg, roll_deg: rollDeg };
      layout = {
        corners_2d: projectRoomCorners(camera.K, pitchDeg, rollDeg, corners3d),
        corners_3d: corners3d,
        source: "manual",
        note: null,
      } as SceneDocument["scene"]["layout"];
    }
  }
  return {
    ...base,
    revision: base.revision + 1,
    scene: { ...base.scene, supports: [...supports.values()], layout, camera },
  } as SceneDocument;
}

// Each test: a session on the scene, its layout draft attached, storage and frames its own.
let frames: ReturnType<typeof manualFrames>;
let storage: MemoryStorage;
let session: SceneSession;
let draft: LayoutDraft;
beforeEach(() => {
  frames = manualFrames();
  storage = new MemoryStorage();
  session = new SceneSession(scene(), { drafts: new DraftStore(storage) });
  draft = new LayoutDraft(session.doc, inPhoto);
  session.attachLayout(draft);
});
afterEach(() => {
  vi.restoreAllMocks();
  vi.unstubAllGlobals();
});

describe("one history for supports and the room layout", () => {
  const dragCorner = (index: number, by: Point2) => {
    const start = draft.beginDrag(index);
    if (!start) throw new Error(`no handle for corner ${index}`);
    draft.moveCorner(index, [start[0] + by[0] / 2, start[1] + by[1] / 2]);
    frames.flush();
    draft.moveCorner(index, [start[0] + by[0], start[1] + by[1]]);
    draft.endDrag();
  };
  const setO1 = (parent: string) =>
    session.edit(`o1 on ${parent}`, [{ kind: "set_support", child: "o1", parent, type: "below" }]);
  const kept = () => new DraftStore(storage).load("s");

  it("undoes and redoes support edits and corner drags in the order they were made", () => {
    const room = draft.live;
    setO1("floor");
    dragCorner(1, [20, 30]);
    const movedRoom = draft.live;
    setO1("wall");
    expect(session.unsavedCount).toBe(2); // o1, and the layout
    expect(session.saveState.kind).toBe("dirty");
    expect(kept()?.layout?.corners[1]).not.toBeNull();

    expect(session.undo()).toBe("o1 on wall");
    expect(session.shown().get("o1")?.parent).toBe("floor");
    expect(draft.dirty).toBe(true);
    expect(session.undo()).toBe("move the room's floor corner 1");
    expect(draft.dirty).toBe(false);
    expect(draft.live).toEqual(room); // the 3D view shows the stored room again
    expect(draft.edit()).toBeNull(); // nothing of the drag is left to save
    expect(kept()?.layout ?? null).toBeNull();
    expect(session.shown().get("o1")?.parent).toBe("floor");
    expect(session.undo()).toBe("o1 on floor");
    expect(session.unsavedCount).toBe(0);
    expect(session.saveState.kind).toBe("clean");
    expect(kept()).toBeNull();

    expect(session.redo()).toBe("o1 on floor");
    expect(session.redo()).toBe("move the room's floor corner 1");
    expect(draft.dirty).toBe(true);
    expect(draft.live?.corners3d).toEqual(movedRoom?.corners3d);
    expect(session.redo()).toBe("o1 on wall");
    expect(session.redo()).toBeNull();
  });

  it("a drag forgets what was undone, like any edit; discard drops the layout too", () => {
    setO1("floor");
    session.undo();
    dragCorner(2, [-10, 12]);
    expect(session.redoLabel).toBeNull();
    setO1("wall");
    session.discard();
    expect(session.unsavedCount).toBe(0);
    expect(draft.dirty).toBe(false);
    session.undo(); // the discard, as one step
    expect(session.unsavedCount).toBe(2);
    expect(draft.dirty).toBe(true);
  });

  it("saves the corners with the support edits; an undo after the save is saved back", async () => {
    const requests: EditRequest[] = [];
    vi.spyOn(api, "postEdits").mockImplementation(async (_id, body) => {
      requests.push(body);
      return stored(session.doc, draft, body);
    });
    const before = session.doc.scene.layout?.corners_2d?.[1] as Point2;
    setO1("floor");
    dragCorner(1, [20, 30]);
    await session.save("ann");
    expect(requests[0]?.edits.map((e) => e.kind)).toEqual(["set_support", "set_layout"]);
    expect(session.doc.revision).toBe(4);
    expect(session.saveState).toEqual({ kind: "saved", revision: 4 });
    expect(draft.dirty).toBe(false);
    expect(kept()).toBeNull();

    // Undo after the save: the corner goes back, and that is an unsaved change to send.
    expect(session.undo()).toBe("move the room's floor corner 1");
    expect(draft.dirty).toBe(true);
    expect(session.saveState.kind).toBe("dirty");
    expect(kept()?.layout?.corners[1]).toEqual(before);
    await session.save("ann");
    const back = requests[1]?.edits.find((e) => e.kind === "set_layout");
    expect(back?.kind === "set_layout" && back.corners_2d[1]).toEqual(before);
    expect(session.doc.revision).toBe(5);
    expect(draft.dirty).toBe(false);
  });

  it("keeps corners moved while a save was on its way unsaved", async () => {
    let answer: (doc: SceneDocument) => void = () => {};
    vi.spyOn(api, "postEdits").mockImplementation(
      (_id, body) =>
        new Promise((resolve) => {
          const doc = stored(session.doc, draft, body);
          answer = () => resolve(doc);
        }),
    );
    dragCorner(1, [20, 30]);
    const saving = session.save("ann");
    dragCorner(2, [5, 5]);
    answer(session.doc);
    await saving;
    expect(draft.dirty).toBe(true);
    expect(session.saveState.kind).toBe("dirty");
    expect(kept()?.layout).not.toBeNull();
  });

  it("still sends moved corners after the layout editor is gone (the page's last save)", async () => {
    const requests: EditRequest[] = [];
    vi.spyOn(api, "postEdits").mockImplementation(async (_id, body) => {
      requests.push(body);
      return stored(session.doc, draft, body);
    });
    const detach = session.attachLayout(draft);
    dragCorner(1, [20, 30]);
    detach(); // leaving the page: the layout editor is disposed before autosave's last save
    expect(session.savable).toBe(true);
    await session.save("ann");
    expect(requests[0]?.edits.map((e) => e.kind)).toEqual(["set_layout"]);
  });

  it("offers moved corners back to the next visit", () => {
    dragCorner(1, [20, 30]);
    const corners = draft.snapshot().corners;
    const next = new SceneSession(scene(), { drafts: new DraftStore(storage) });
    const nextDraft = new LayoutDraft(next.doc, inPhoto);
    next.attachLayout(nextDraft);
    expect(next.recovered?.layout?.corners).toEqual(corners);
    next.restoreRecovered();
    expect(nextDraft.dirty).toBe(true);
    expect(nextDraft.snapshot().corners).toEqual(corners);
    expect(next.notice).toContain("Restored 1 unsaved change");
    next.undo();
    expect(nextDraft.dirty).toBe(false);
  });
});

describe("read-only scenes", () => {
  it("locks a submitted scene: no edit, no undo, no layout editing, and says why", () => {
    session.edit("o1 on floor", [
      { kind: "set_support", child: "o1", parent: "floor", type: "below" },
    ]);
    draft.setEditing(true);
    const changes: string[] = [];
    session.subscribe((change) => changes.push(change));
    session.setWorkflow(
      workflow("submitted", {
        editable: false,
        editable_reason: "the scene is submitted for review",
      }),
    );
    expect(changes).toContain("lock");
    expect(session.editable).toBe(false);
    expect(session.lock).toEqual({
      title: "Submitted for review — read only",
      reason: "the scene is submitted for review",
    });
    expect(draft.editing).toBe(false);
    session.edit("o0 on wall", [
      { kind: "set_support", child: "o0", parent: "wall", type: "behind" },
    ]);
    expect(session.pending.map((e) => e.child)).toEqual(["o1"]); // kept, nothing added
    expect(session.message).toBe(
      "Submitted for review — read only: the scene is submitted for review",
    );
    expect(session.undo()).toBeNull();
    expect(session.pending).toHaveLength(1);

    // Sent back by the reviewer and taken again: editable, the kept edit still there.
    session.setWorkflow(workflow("in_annotation", { editable: true }));
    expect(session.editable).toBe(true);
    expect(session.undo()).toBe("o1 on floor");
  });

  it("follows the server's latest word, the scene's or the workflow's", () => {
    const locked = { ...scene(), editable: false, editable_reason: "bob is annotating this scene" };
    const other = new SceneSession(locked as SceneDocument, { drafts: new DraftStore(storage) });
    expect(other.lock).toEqual({ title: "Read only", reason: "bob is annotating this scene" });
    other.setWorkflow(workflow("in_annotation", { editable: true })); // an admin took it over
    expect(other.editable).toBe(true);
  });

  it("without the server's word, submitted and accepted scenes are read only", () => {
    session.setWorkflow(workflow("accepted"));
    expect(session.lock?.title).toBe("Accepted — read only");
    session.setWorkflow(workflow("rejected"));
    expect(session.editable).toBe(true);
  });

  it("keeps the edits the server refused (409) and shows its message; saves them once editable", async () => {
    session.setWorkflow(workflow("in_annotation", { editable: true }));
    const message = "the scene is submitted for review (by ann): it cannot be edited";
    const post = vi.spyOn(api, "postEdits").mockRejectedValueOnce(new ConflictError({ message }));
    session.edit("o1 on floor", [
      { kind: "set_support", child: "o1", parent: "floor", type: "below" },
    ]);
    await session.save("ann");
    expect(session.saveState).toEqual({ kind: "error", message, retry: false });
    expect(session.pending).toHaveLength(1);
    expect(new DraftStore(storage).load("s")?.edits).toHaveLength(1);
    expect(session.lock).toEqual({ title: "Read only", reason: message });

    // The workflow, read again, says why; later the scene is editable again.
    session.setWorkflow(workflow("submitted", { editable: false, editable_reason: message }));
    expect(session.lock?.title).toBe("Submitted for review — read only");
    post.mockImplementation(async (_id, body) => stored(session.doc, draft, body));
    session.setWorkflow(workflow("in_annotation", { editable: true }));
    expect(session.editable).toBe(true);
    expect(session.saveState.kind).toBe("dirty"); // autosave takes it from here
    await session.save("ann");
    expect(session.pending).toHaveLength(0);
  });
});
