// Revision diffs name each kind of change, and revert gives back exactly the old supports.
import type { Scene, SupportRelation } from "@holiscene/schema";
import { describe, expect, it } from "vitest";
import { supportRelation } from "../testing/supports";
import { describeChange, diffScenes, diffSupports } from "./revisionDiff";

const rel = supportRelation;

const scene = (supports: SupportRelation[], ids = ["o0", "o1", "o2", "o3"]): Scene =>
  ({
    schema_version: 1,
    name: "t",
    image: { file: "i.png", width: 10, height: 10 },
    objects: ids.map((id) => ({ id, class: "box", bbox: [0, 0, 1, 1] })),
    supports,
  }) as unknown as Scene;

describe("revision diff", () => {
  const manual = { source: "manual" as const, author: "ann", confidence: null, time: "t1" };
  const before = [rel("o0", "floor"), rel("o1", "o0"), rel("o2", "floor"), rel("o3", "o0")];
  const after = [
    rel("o0", "floor", manual), // confirmed
    rel("o1", "o2", manual), // moved
    rel("o2", "floor", { ...manual, type: "behind" }), // retyped
    // o3 removed
  ];

  it("names each change", () => {
    const changes = diffSupports(before, after);
    expect(changes.map((c) => [c.child, c.kind])).toEqual([
      ["o0", "confirmed"],
      ["o1", "moved"],
      ["o2", "retyped"],
      ["o3", "removed"],
    ]);
    expect(describeChange(changes[1] as (typeof changes)[number])).toBe(
      "o1: new supporter: on o0 (below, predicted 70%) → on o2 (below, by ann)",
    );
    expect(diffSupports(after, before).at(-1)?.kind).toBe("added");
    expect(diffSupports(before, before)).toEqual([]);
  });

  it("notices objects and the layout", () => {
    const a = scene(before);
    const b = {
      ...scene(after, ["o0", "o1", "o2", "o4"]),
      layout: { corners_2d: [] },
    } as unknown as Scene;
    const diff = diffScenes(a, b);
    expect(diff.objectsAdded).toEqual(["o4"]);
    expect(diff.objectsRemoved).toEqual(["o3"]);
    expect(diff.layoutChanged).toBe(true);
    expect(diff.objectsChanged).toEqual([]);
  });

  it("names what changed of each object kept: class, box, mask, and 3D box or shape apart", () => {
    const a = scene(before);
    const [o0, o1, o2] = a.objects;
    if (!o0 || !o1 || !o2) throw new Error("objects");
    const b = {
      ...a,
      objects: [
        { ...o0, class: "night_stand", mask: { origin: [0, 0], size: [1, 1], rle: [0, 1] } },
        { ...o1, bbox: [0, 0, 2.4, 1.6] },
        {
          ...o2,
          source_class: "crate",
          box_3d: { center: [0, 0, 2], size: [1, 1, 1], yaw: 0 },
        },
        ...a.objects.slice(3),
      ],
    } as unknown as Scene;
    expect(diffScenes(a, b).objectsChanged).toEqual([
      { id: "o0", drawn: ["class box → night stand", "mask redrawn"], placed: [] },
      { id: "o1", drawn: ["box 0,0–1,1 → 0,0–2,2"], placed: [] },
      { id: "o2", drawn: ["class box → box (crate)"], placed: ["3D box"] },
    ]);
  });
});
