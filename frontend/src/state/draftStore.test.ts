// Drafts are each person's own: another person signing in on the same browser is not offered
// them; drafts stored before they had owners go, once, to whoever opens the scene first.
import { describe, expect, it } from "vitest";
import { MemoryStorage } from "../testing/memoryStorage";
import { type Draft, DraftStore, type FailedObjectAction } from "./draftStore";

const draft = (child: string): Draft => ({
  sceneId: "s1",
  baseRevision: 3,
  edits: [{ kind: "set_support", child, parent: "floor", type: "below" }],
  savedAt: "2026-12-07T01:00:00.000Z",
});

const failed: FailedObjectAction = {
  label: "move o2",
  message: "the server could not be reached",
  edits: [{ kind: "set_bbox", id: "o2", bbox: [1, 2, 30, 40] }],
  failedAt: "2026-12-07T01:00:00.000Z",
};

describe("draft store", () => {
  it("keeps one person's unsaved edits from everyone else", () => {
    const storage = new MemoryStorage();
    new DraftStore(storage, "ann").save(draft("o1"));
    new DraftStore(storage, "ann").saveFailedAction("s1", failed);
    const bob = new DraftStore(storage, "bob");
    expect(bob.takeForRecovery("s1")).toBeNull();
    expect(bob.loadFailedAction("s1")).toBeNull();
    // Still there for Ann when she comes back.
    const ann = new DraftStore(storage, "ann");
    expect(ann.takeForRecovery("s1")?.edits.map((e) => e.child)).toEqual(["o1"]);
    expect(ann.loadFailedAction("s1")?.label).toBe("move o2");
  });

  it("gives drafts stored before they had owners to the first person, merged with theirs", () => {
    const storage = new MemoryStorage();
    new DraftStore(storage, null).save(draft("o1"));
    new DraftStore(storage, null).saveFailedAction("s1", failed);
    new DraftStore(storage, "ann").save(draft("o4"));
    const ann = new DraftStore(storage, "ann");
    const taken = ann.takeForRecovery("s1");
    expect(taken?.edits.map((e) => e.child).sort()).toEqual(["o1", "o4"]);
    expect(ann.loadFailedAction("s1")?.label).toBe("move o2");
    const bob = new DraftStore(storage, "bob");
    expect(bob.takeForRecovery("s1")).toBeNull();
    expect(bob.loadFailedAction("s1")).toBeNull();
    // Ann's set-aside edits stay hers until she restores or discards them.
    expect(new DraftStore(storage, "ann").takeForRecovery("s1")?.edits).toHaveLength(2);
  });
});
