// The scene as an object action will leave it, before the server answers.
import type { SceneDocument, SceneObject, SupportRelation } from "@holiscene/schema";
import { describe, expect, it } from "vitest";
import { sceneDocument, sceneObject } from "../testing/sceneDocuments";
import { supportRelation } from "../testing/supports";
import { predictDocument } from "./objectPrediction";

const object = (id: string, cls = "chair") => sceneObject(id, cls);
const documentOf = (revision: number, objects: SceneObject[], supports: SupportRelation[]) =>
  sceneDocument(objects, supports, { revision });

const table = object("t", "table");
const cup = object("c", "otherprop");
const lamp = object("l", "lamp");
const original = documentOf(
  3,
  [table, cup, lamp],
  [supportRelation("t", "floor"), supportRelation("c", "t"), supportRelation("l", "t")],
);
const none = () => undefined;
const ids = (doc: SceneDocument | null) => doc?.scene.objects?.map((o) => o.id);
const edges = (doc: SceneDocument | null) =>
  doc?.scene.supports?.map((s) => `${s.child}>${s.parent}`).sort();

describe("predictDocument", () => {
  it("a removal takes the object and every support it took part in", () => {
    const after = predictDocument(original, [{ kind: "remove_object", id: "t" }], none);
    expect(ids(after)).toEqual(["c", "l"]);
    expect(edges(after)).toEqual([]);
    expect(after?.revision).toBe(3);
    expect(original.scene.objects).toHaveLength(3); // the loaded revision is left alone
  });

  it("a class is shown as stored (aliases mapped), a box as given", () => {
    const after = predictDocument(
      original,
      [
        { kind: "set_class", id: "c", class: "Coffee Table" },
        { kind: "set_bbox", id: "l", bbox: [1, 2, 3, 4] },
      ],
      none,
    );
    expect(after?.scene.objects?.find((o) => o.id === "c")?.class).toBe("table");
    expect(after?.scene.objects?.find((o) => o.id === "l")?.bbox).toEqual([1, 2, 3, 4]);
  });

  it("a new object is shown by its box (its mask comes with the answer), after the others", () => {
    const after = predictDocument(
      original,
      [
        {
          kind: "add_object",
          id: "d1",
          class: "Coffee Table",
          bbox: [0, 0, 5, 5],
          source: "manual",
        },
        {
          kind: "add_object",
          id: "d2",
          class: "bed",
          bbox: [1, 1, 9, 9],
          source: "detector",
          score: 0.7,
        },
      ],
      none,
    );
    expect(ids(after)).toEqual(["t", "c", "l", "d1", "d2"]);
    const [d1, d2] = after?.scene.objects?.slice(3) ?? [];
    expect(d1).toMatchObject({ class: "table", bbox: [0, 0, 5, 5], mask: null, source: "manual" });
    expect(d2).toMatchObject({
      class: "bed",
      score: 0.7,
      source: "detector",
      set_by_person: ["object"],
    });
    expect(edges(after)).toEqual(edges(original));
  });

  it("what cannot be foreseen is not predicted", () => {
    expect(
      predictDocument(original, [{ kind: "set_class", id: "c", class: "spaceship" }], none),
    ).toBeNull();
    expect(predictDocument(original, [{ kind: "remove_object", id: "zz" }], none)).toBeNull();
    expect(
      predictDocument(
        original,
        [{ kind: "add_object", id: "t", class: "bed", bbox: [0, 0, 5, 5], source: "manual" }],
        none,
      ),
    ).toBeNull();
    expect(
      predictDocument(original, [{ kind: "restore_object", id: "t", from_revision: 2 }], none),
    ).toBeNull();
  });

  it("a restore from a revision at hand brings the object and its supports back", () => {
    const removed = predictDocument(original, [{ kind: "remove_object", id: "t" }], none);
    if (!removed) throw new Error("predicted");
    const restored = predictDocument(
      { ...removed, revision: 4 },
      [{ kind: "restore_object", id: "t", from_revision: 3 }],
      (n) => (n === 3 ? original : undefined),
    );
    expect(ids(restored)?.sort()).toEqual(["c", "l", "t"]);
    expect(edges(restored)).toEqual(edges(original));
  });

  it("a revert to a revision at hand shows that revision's scene on this one's photo", () => {
    const removed = predictDocument(original, [{ kind: "remove_object", id: "t" }], none);
    if (!removed) throw new Error("predicted");
    const later = { ...removed, revision: 4, scene: { ...removed.scene, name: "renamed" } };
    const edit = { kind: "restore_scene", from_revision: 3 } as const;
    const reverted = predictDocument(later, [edit], (n) => (n === 3 ? original : undefined));
    expect(ids(reverted)).toEqual(["t", "c", "l"]);
    expect(edges(reverted)).toEqual(edges(original));
    expect(reverted?.scene.layout).toEqual(original.scene.layout);
    expect(reverted?.scene.name).toBe("renamed");
    expect(reverted?.revision).toBe(4);
    expect(predictDocument(later, [edit], none)).toBeNull();
  });
});
