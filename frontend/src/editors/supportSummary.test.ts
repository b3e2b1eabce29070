// The summary never calls a scene with nothing to support "all supported".
import type { SceneObject } from "@holiscene/schema";
import { describe, expect, it } from "vitest";
import { supportSummary } from "./supportSummary";

const object = (id: string, cls: string) =>
  ({ id, class: cls, bbox: [0, 0, 1, 1] }) as unknown as SceneObject;

describe("support summary", () => {
  it("tells an empty scene to get objects, as a warning", () => {
    const summary = supportSummary([], 0);
    expect(summary.text).toMatch(/^No objects yet\. Accept the detector's suggested boxes/);
    expect(summary.text).toContain("Box tool (B)"); // when the detector finds nothing
    expect(summary.text).not.toContain("supported");
    expect(summary.warn).toBe(true);
  });

  it("points at the action waiting for a retry instead of asking for objects again", () => {
    const summary = supportSummary([], 0, "add bed");
    expect(summary.text).toMatch(/^No objects shown yet: "add bed" has no answer/);
    expect(summary.text).toContain("Press Retry under the photo tools");
    expect(summary.text).not.toContain("Detect objects");
    expect(summary.warn).toBe(true);
    // Once objects are shown, the count is what matters.
    expect(supportSummary([object("o0", "bed")], 1, "add lamp").text).toBe(
      "1 object · 1 without a supporter",
    );
  });

  it("tells a scene of walls only that it has nothing to support", () => {
    const summary = supportSummary([object("w", "wall"), object("f", "floor")], 0);
    expect(summary.text).toMatch(/^No objects to support, only the room's walls/);
    expect(summary.text).not.toContain("all supported");
    expect(summary.warn).toBe(true);
  });

  it("counts the objects that need a supporter and those without one", () => {
    const objects = [object("o0", "table"), object("o1", "lamp"), object("w", "wall")];
    expect(supportSummary(objects, 0)).toEqual({ text: "2 objects · all supported", warn: false });
    expect(supportSummary(objects, 1)).toEqual({
      text: "2 objects · 1 without a supporter",
      warn: true,
    });
    expect(supportSummary(objects.slice(1), 0).text).toBe("1 object · all supported");
  });
});
