// One Undo over several histories: the most recent action is taken back first, whichever
// history holds it; redo follows the undos back, and not past a newer action.
import { describe, expect, it } from "vitest";
import { EditHistory } from "./editHistory";
import { latestRedo, latestUndo } from "./undoOrder";

const step = (label: string) => ({ label, changes: [{ key: "k", before: 0, after: 1 }] });

describe("undoOrder", () => {
  it("undoes across histories newest first and redoes in the opposite order", () => {
    const supports = new EditHistory<number>();
    const objects = new EditHistory<number>();
    supports.record(step("support 1"));
    objects.record(step("object 1"));
    supports.record(step("support 2"));
    const both = [supports, objects];

    const order: string[] = [];
    for (let i = 0; i < 3; i++) {
      const history = latestUndo(both);
      order.push(history?.undoLabel ?? "");
      history?.undo();
    }
    expect(order).toEqual(["support 2", "object 1", "support 1"]);
    expect(latestUndo(both)).toBeNull();

    const redone: string[] = [];
    for (let i = 0; i < 3; i++) {
      const history = latestRedo(both);
      redone.push(history?.redoLabel ?? "");
      history?.redo();
    }
    expect(redone).toEqual(["support 1", "object 1", "support 2"]);
    expect(latestRedo(both)).toBeNull();
  });

  it("a new action in one history ends redo in the other", () => {
    const supports = new EditHistory<number>();
    const objects = new EditHistory<number>();
    objects.record(step("object 1"));
    objects.undo();
    expect(latestRedo([supports, objects])?.redoLabel).toBe("object 1");
    supports.record(step("support 1"));
    expect(latestRedo([supports, objects])).toBeNull();
    expect(latestUndo([supports, objects])?.undoLabel).toBe("support 1");
  });
});
