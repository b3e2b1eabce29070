// "Mine to do" lists what the person holds, what was sent back to them first.
import type { SceneSummary } from "@holiscene/schema";
import { describe, expect, it } from "vitest";
import { myWork, sentBack, sentBackText } from "./myWork";

const scene = (id: string, state: SceneSummary["state"], assignee: string | null) =>
  ({ id, name: `scene ${id}`, state, assignee }) as SceneSummary;

describe("mine to do", () => {
  const scenes = [
    scene("a", "in_annotation", "ann"),
    scene("b", "submitted", "ann"),
    scene("c", "rejected", "ann"),
    scene("d", "in_annotation", "bob"),
    scene("e", "predicted", null),
    scene("f", "accepted", "ann"),
    scene("g", "rejected", "ann"),
  ];

  it("keeps the scenes the person annotates or must fix, the sent-back ones first", () => {
    expect(myWork(scenes, "ann").map((s) => s.id)).toEqual(["c", "g", "a"]);
  });

  it("is empty for someone holding nothing, or nobody", () => {
    expect(myWork(scenes, "eve")).toEqual([]);
    expect(myWork(scenes, null)).toEqual([]);
  });

  it("names the scenes sent back to the person, a few of them", () => {
    expect(sentBack(scenes, "ann").map((s) => s.id)).toEqual(["c", "g"]);
    expect(sentBack(scenes, null)).toEqual([]);
    expect(sentBackText(sentBack(scenes, "ann"))).toBe(
      "2 scenes were sent back to you by a reviewer: scene c, scene g.",
    );
    const many = ["p", "q", "r", "s", "t"].map((id) => scene(id, "rejected", "ann"));
    expect(sentBackText(many.slice(0, 1))).toBe(
      "1 scene was sent back to you by a reviewer: scene p.",
    );
    expect(sentBackText(many)).toMatch(/: scene p, scene q, scene r and 2 more\.$/);
  });
});
