// The conflict message names who saved meanwhile: the person themselves, in another tab, too.
import { describe, expect, it } from "vitest";
import type { SaveState } from "../../state/sceneSession";
import { conflictText } from "./conflictPanel";

type Conflict = Extract<SaveState, { kind: "conflict" }>;

const conflict = (authors: string[]): Conflict =>
  ({
    kind: "conflict",
    baseRevision: 3,
    currentRevision: 4,
    message: "",
    theirs: authors.map((author, i) => ({ revision: 4 + i, author })),
  }) as unknown as Conflict;

describe("the conflict message", () => {
  it("names the other people who saved", () => {
    expect(conflictText(conflict(["bob"]), 1, "ann")).toMatch(
      /^bob saved this scene after you loaded revision 3 \(the latest is revision 4\)\. Your 1 change was not saved/,
    );
  });

  it("tells a person their own save from another tab or window", () => {
    expect(conflictText(conflict(["ann", "bob"]), 2, "ann")).toMatch(
      /^You \(in another tab or window\), bob saved this scene/,
    );
  });
});
