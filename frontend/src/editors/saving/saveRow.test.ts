import { describe, expect, it } from "vitest";
import { statusText } from "./saveRow";

describe("the save status", () => {
  it("says an object action is being saved rather than that nothing is left to save", () => {
    expect(statusText({ kind: "clean" }, 0, 4, "auto", "add chair o3")).toBe(
      "Saving: add chair o3…",
    );
    expect(statusText({ kind: "saved", revision: 5 }, 0, 5, "auto", "delete table o1")).toBe(
      "Saving: delete table o1…",
    );
  });

  it("says what it said before once the object action is saved", () => {
    expect(statusText({ kind: "clean" }, 0, 4, "auto", null)).toBe(
      "Revision 4 · no unsaved changes",
    );
    expect(statusText({ kind: "saved", revision: 5 }, 0, 5, "auto", null)).toBe(
      "Saved as revision 5",
    );
  });

  it("names the latest revision once object actions have saved after the last save", () => {
    // A support edit saved revision 14, then a mask and a class were saved as 15 and 16.
    expect(statusText({ kind: "saved", revision: 14 }, 0, 16, "auto", null)).toBe(
      "Saved as revision 16",
    );
  });

  it("says an object action kept after it failed is not saved, beside unsaved support edits too", () => {
    expect(statusText({ kind: "saved", revision: 5 }, 0, 5, "auto", null, "remove door o9")).toBe(
      "Not saved: remove door o9 (above the photo)",
    );
    expect(statusText({ kind: "dirty" }, 1, 5, "auto", null, "remove door o9")).toBe(
      "1 unsaved change on revision 5 · autosaving · not saved: remove door o9",
    );
  });

  it("keeps unsaved support edits and errors in front of an object action", () => {
    expect(statusText({ kind: "dirty" }, 2, 4, "auto", "add chair o3")).toBe(
      "2 unsaved changes on revision 4 · autosaving",
    );
    // Held after a conflict's reload: nothing goes by itself, and the line says so.
    expect(statusText({ kind: "dirty" }, 2, 19, "held", null)).toBe(
      "2 unsaved changes on revision 19 · held after the reload: review, then Save (Ctrl+S)",
    );
    expect(statusText({ kind: "dirty" }, 12, 4, "undiscarded", null)).toBe(
      "12 unsaved changes on revision 4 · brought back by Undo after Discard, not saved: " +
        "Save (Ctrl+S) keeps them",
    );
    expect(
      statusText(
        { kind: "conflict", baseRevision: 4, currentRevision: 5, message: "", theirs: [] },
        1,
        4,
        "auto",
        "add chair o3",
      ),
    ).toBe("Not saved: conflict");
  });
});
