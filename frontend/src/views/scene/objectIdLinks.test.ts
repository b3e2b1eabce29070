import { describe, expect, it } from "vitest";
import { textWithObjectIds } from "./objectIdLinks";

describe("textWithObjectIds", () => {
  it("cuts a text at the ids of the scene's objects, and only at those", () => {
    const ids = new Set(["o3", "o5", "o4_1"]);
    expect(textWithObjectIds("keep their box: o3, o5, o4_1 and o9 (o3)", ids)).toEqual([
      { text: "keep their box: " },
      { id: "o3" },
      { text: ", " },
      { id: "o5" },
      { text: ", " },
      { id: "o4_1" },
      { text: " and " },
      { removed: "o9" },
      { text: " (" },
      { id: "o3" },
      { text: ")" },
    ]);
    expect(textWithObjectIds("no objects", ids)).toEqual([{ text: "no objects" }]);
    // Words that only look alike stay text.
    expect(textWithObjectIds("door ok2 o3x", ids)).toEqual([{ text: "door ok2 o3x" }]);
  });
});
