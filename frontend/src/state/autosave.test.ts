// Autosave's timing on a stand-in session (the real one needs a server to save to): it saves
// after the idle time, waits again after each edit, stops on a conflict, retries a failed save
// but not a refused one, holds while asked to or while the scene is read only, and saves once
// more when the page leaves (after a save on its way), and sends a save refused for an ended session once the person has
// logged in again (never under someone else's session).
import { afterEach, beforeEach, describe, expect, it, vi } from "vitest";
import { startAutosave } from "./autosave";
import { setCurrentUser } from "./currentUser";
import type { AutosaveHold, Change, SaveState, SceneSession } from "./sceneSession";

class StandIn {
  pending: unknown[] = [];
  saveState: SaveState = { kind: "clean" };
  holdAutosave: AutosaveHold | null = null;
  editable = true;
  /** Whose edits (null: drafts stored before they had owners). */
  drafts = { owner: null as string | null };
  get savable() {
    return this.pending.length > 0;
  }
  saves = 0;
  private listener: ((change: Change) => void) | null = null;
  subscribe(listener: (change: Change) => void) {
    this.listener = listener;
    return () => {
      this.listener = null;
    };
  }
  edit() {
    this.pending.push({});
    this.saveState = { kind: "dirty" };
    this.listener?.("edits");
  }
  settle(state: SaveState) {
    this.saveState = state;
    this.listener?.("save");
  }
  async save() {
    this.saves += 1;
  }
}

describe("autosave", () => {
  let session: StandIn;
  let stop: () => void;
  beforeEach(() => {
    vi.useFakeTimers();
    session = new StandIn();
    stop = startAutosave(session as unknown as SceneSession, {
      author: () => "ann",
      delayMs: 1000,
      retryMs: 5000,
    });
  });
  afterEach(() => {
    stop();
    vi.useRealTimers();
  });

  it("saves after the idle time, counted from the last edit", () => {
    session.edit();
    vi.advanceTimersByTime(900);
    session.edit();
    vi.advanceTimersByTime(900);
    expect(session.saves).toBe(0);
    vi.advanceTimersByTime(100);
    expect(session.saves).toBe(1);
    vi.advanceTimersByTime(10_000);
    expect(session.saves).toBe(1);
  });

  it("does not save in a conflict, nor while held", () => {
    session.edit();
    session.settle({
      kind: "conflict",
      baseRevision: 2,
      currentRevision: 3,
      message: "",
      theirs: [],
    });
    vi.advanceTimersByTime(5000);
    expect(session.saves).toBe(0);
    session.holdAutosave = "reload";
    session.settle({ kind: "dirty" });
    vi.advanceTimersByTime(5000);
    expect(session.saves).toBe(0);
  });

  it("retries a save that failed on the way, not one the server refused", () => {
    session.edit();
    vi.advanceTimersByTime(1000);
    session.settle({ kind: "error", message: "offline", retry: true });
    vi.advanceTimersByTime(4999);
    expect(session.saves).toBe(1);
    vi.advanceTimersByTime(1);
    expect(session.saves).toBe(2);
    session.settle({ kind: "error", message: "not allowed", retry: false });
    vi.advanceTimersByTime(60_000);
    expect(session.saves).toBe(2);
  });

  it("sends a save refused because the session ended once the person has logged in again", () => {
    session.edit();
    vi.advanceTimersByTime(1000);
    session.settle({ kind: "error", message: "log in first", retry: false });
    vi.advanceTimersByTime(60_000);
    expect(session.saves).toBe(1);
    setCurrentUser({ name: "ann", role: "annotator", local_mode: false });
    vi.advanceTimersByTime(1000);
    expect(session.saves).toBe(2);
    setCurrentUser(null); // logging out sends nothing
    vi.advanceTimersByTime(60_000);
    expect(session.saves).toBe(2);
  });

  it("never saves one person's edits under another's session", () => {
    session.drafts.owner = "ann";
    setCurrentUser({ name: "ann", role: "annotator", local_mode: false });
    session.edit();
    vi.advanceTimersByTime(1000);
    expect(session.saves).toBe(1);
    session.settle({ kind: "error", message: "log in first", retry: false });
    // Bob logs in over Ann's page: her edits wait for her, neither sent now nor on leaving.
    setCurrentUser({ name: "bob", role: "admin", local_mode: false });
    session.edit();
    vi.advanceTimersByTime(60_000);
    stop();
    stop = () => {};
    expect(session.saves).toBe(1);
    setCurrentUser(null);
  });

  it("sends nothing while the scene is read only, and saves the kept edits once it is not", () => {
    session.editable = false;
    session.edit();
    vi.advanceTimersByTime(60_000);
    expect(session.saves).toBe(0);
    session.editable = true; // the session says "dirty" again when its lock lifts
    session.settle({ kind: "dirty" });
    vi.advanceTimersByTime(1000);
    expect(session.saves).toBe(1);
  });

  it("saves what is left when the page leaves", () => {
    session.edit();
    stop();
    expect(session.saves).toBe(1);
    stop = () => {};
  });

  it("when the page leaves during a save, sends the edits made meanwhile once it has landed", async () => {
    session.edit();
    vi.advanceTimersByTime(1000);
    expect(session.saves).toBe(1);
    session.saveState = { kind: "saving" }; // that save is on its way
    session.edit(); // a corner dragged meanwhile
    session.saveState = { kind: "saving" };
    stop();
    stop = () => {};
    expect(session.saves).toBe(1); // not on top of the save on its way
    session.settle({ kind: "saved", revision: 4 });
    await Promise.resolve();
    await Promise.resolve();
    expect(session.saves).toBe(2);
  });

  it("waits while an object action is being saved, and saves right after it", () => {
    stop();
    let objectSaving = true;
    stop = startAutosave(session as unknown as SceneSession, {
      author: () => "ann",
      delayMs: 1000,
      otherSaving: () => objectSaving,
    });
    session.edit();
    vi.advanceTimersByTime(3000);
    expect(session.saves).toBe(0);
    // Once the object action is saved, the support edits follow on its revision.
    objectSaving = false;
    vi.advanceTimersByTime(250);
    expect(session.saves).toBe(1);
  });
});
