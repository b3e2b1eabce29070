// Object colours: every object of a crowded scene its own colour, the same after objects are
// added, and class colouring gives objects of one class one colour.
import { describe, expect, it } from "vitest";
import { classColours, maskColours, objectColours } from "./objectColors";
import type { Rgb } from "./rgb";

const distance = (a: Rgb, b: Rgb) => Math.hypot(a[0] - b[0], a[1] - b[1], a[2] - b[2]);

function closest(colours: Map<string, Rgb>): number {
  const list = [...colours.values()];
  let min = Number.POSITIVE_INFINITY;
  list.forEach((a, i) => {
    for (const b of list.slice(i + 1)) min = Math.min(min, distance(a, b));
  });
  return min;
}

const hue = ([r, g, b]: Rgb) => {
  const max = Math.max(r, g, b);
  const span = max - Math.min(r, g, b);
  const h = max === r ? (g - b) / span : max === g ? 2 + (b - r) / span : 4 + (r - g) / span;
  return (h * 60 + 360) % 360;
};

const ids = (n: number, prefix = "o") =>
  Array.from({ length: n }, (_, i) => ({ id: `${prefix}${i}` }));

describe("object colours", () => {
  it("gives the 25 objects of a crowded scene 25 clearly different colours", () => {
    for (const prefix of ["o", "obj_", "chair-"]) {
      const colours = objectColours(ids(25, prefix));
      expect(new Set([...colours.values()].map(String)).size).toBe(25);
      expect(closest(colours)).toBeGreaterThan(30);
    }
  });

  it("gives a numbered series (the pipeline's o0, o1, ...) neighbouring, far-apart slots", () => {
    expect(closest(objectColours(ids(10)))).toBeGreaterThan(40);
    expect(closest(objectColours(ids(10, "d")))).toBeGreaterThan(40);
  });

  it("gives the detector's d1, d2 ... hues apart from the pipeline's o0, o1 ... beside them", () => {
    const colours = [...objectColours([...ids(6), ...ids(4, "d").slice(1)]).values()];
    colours.forEach((a, i) => {
      for (const b of colours.slice(i + 1)) {
        const d = Math.abs(hue(a) - hue(b));
        expect(Math.min(d, 360 - d)).toBeGreaterThan(20);
      }
    });
  });

  it("keeps the colours of existing objects when one is added or the page reloads", () => {
    const before = objectColours(ids(12));
    const after = objectColours([...ids(12), { id: "new_box" }]);
    for (const [id, colour] of before) expect(after.get(id)).toEqual(colour);
    expect(objectColours(ids(12))).toEqual(before);
  });

  it("keeps the other objects' colours when a person removes one", () => {
    // The pipeline's o0..o9 and the detector's d1..d4 beside them, where some took another
    // slot than their own; each removal in turn leaves every other colour as it was.
    const scene = [...ids(10), ...ids(5, "d").slice(1)];
    const before = objectColours(scene);
    for (const gone of scene) {
      const left = scene.filter((o) => o.id !== gone.id);
      const after = objectColours(left, [gone.id]);
      for (const o of left)
        expect(after.get(o.id), `${o.id} after ${gone.id}`).toEqual(before.get(o.id));
    }
    // Without the removed list, a removal moves some (what people saw: o7 took o6's blue).
    const moved = scene.some((gone) => {
      const left = scene.filter((o) => o.id !== gone.id);
      const after = objectColours(left);
      return left.some((o) => String(after.get(o.id)) !== String(before.get(o.id)));
    });
    expect(moved).toBe(true);
  });

  it("colours by class on request", () => {
    const objects = [
      { id: "a", class: "chair" as const },
      { id: "b", class: "chair" as const },
      { id: "c", class: "table" as const },
    ];
    const byClass = maskColours(objects, "class");
    expect(byClass.get("a")).toEqual(classColours(["chair"]).get("chair"));
    expect(byClass.get("b")).toEqual(byClass.get("a"));
    expect(byClass.get("c")).not.toEqual(byClass.get("a"));
    const byObject = maskColours(objects, "object");
    expect(byObject.get("b")).not.toEqual(byObject.get("a"));
  });

  it("gives the classes of a scene hues apart, each its own colour where none is near", () => {
    // Books, bookshelf and shelves (one green each before) and sofa beside picture.
    const crowded = [
      ...["books", "bookshelf", "shelves", "sofa", "picture", "chair", "table", "lamp"],
      ...["pillow", "box", "otherprop"],
    ];
    const colours = classColours(crowded);
    const hues = [...colours.values()].map(hue);
    hues.forEach((a, i) => {
      for (const b of hues.slice(i + 1)) {
        const d = Math.abs(a - b);
        expect(Math.min(d, 360 - d)).toBeGreaterThan(20);
      }
    });
    // A lamp's and a pillow's were a purple and a blue 15 degrees apart.
    const apart = (a: string, b: string) => {
      const d = Math.abs(hue(colours.get(a) as Rgb) - hue(colours.get(b) as Rgb));
      return Math.min(d, 360 - d);
    };
    expect(apart("lamp", "pillow")).toBeGreaterThan(40);
    // The most common class keeps the colour it has alone; the order given does not matter.
    expect(colours.get("chair")).toEqual(classColours(["chair"]).get("chair"));
    expect(classColours([...crowded].reverse())).toEqual(colours);
    // A class from outside the vocabulary still gets a colour of its own.
    expect(classColours(["chair", "hammock"]).get("hammock")).not.toEqual(colours.get("chair"));
  });
});
