import type { SceneObject } from "@holiscene/schema";
import { describe, expect, it } from "vitest";
import type { DetectedBox } from "../../inference/detectorTensor";
import { addObjectEdit, freshIds, offerLabel, offersOf, openOffers } from "./detectionOffers";

const box = (cls: string, bbox: [number, number, number, number], score: number): DetectedBox => ({
  cls,
  bbox,
  score,
  sourceClass: cls,
});

const object = (id: string, cls: string, bbox: [number, number, number, number]) =>
  ({ id, class: cls, bbox, mask: null }) as unknown as SceneObject;

describe("detection offers", () => {
  const offers = offersOf([
    box("chair", [0, 0, 100, 100], 0.4),
    box("table", [200, 200, 300, 300], 0.9),
    box("chair", [300, 0, 400, 100], 0.6),
  ]);

  it("are the detector's boxes, best first", () => {
    expect(offers.map((o) => `${o.key} ${offerLabel(o)}`)).toEqual([
      "s1 table 90%",
      "s2 chair 60%",
      "s3 chair 40%",
    ]);
  });

  it("leave out boxes over an object of their class (IoU > 0.5) or a rejected one", () => {
    const objects = [
      object("o1", "chair", [0, 0, 100, 60]), // IoU 0.6 with s3
      object("o2", "sofa", [300, 0, 400, 60]), // another class over s2 (IoU 0.6)
      object("o3", "table", [200, 200, 300, 250]), // IoU exactly 0.5 with s1: still offered
    ];
    expect(openOffers(offers, objects).map((o) => o.key)).toEqual(["s1", "s2"]);
    const rejected = offers.filter((o) => o.key === "s2");
    expect(openOffers(offers, objects, rejected).map((o) => o.key)).toEqual(["s1"]);
  });

  it("leave out anything at the same place (IoU > 0.7) whatever its class", () => {
    const crowded = offersOf([
      box("books", [0, 0, 100, 100], 0.5),
      box("box", [0, 0, 100, 90], 0.3), // IoU 0.9 with the better "books"
      box("lamp", [300, 0, 400, 100], 0.4),
    ]);
    expect(openOffers(crowded, []).map((o) => o.cls)).toEqual(["books", "lamp"]);
    const objects = [object("o1", "table", [300, 0, 400, 95])]; // IoU 0.95 with the lamp
    expect(openOffers(crowded, objects).map((o) => o.cls)).toEqual(["books"]);
  });

  it("take new ids that no object has", () => {
    const objects = [object("d1", "chair", [0, 0, 1, 1]), object("d3", "chair", [0, 0, 1, 1])];
    expect(freshIds(objects, 3)).toEqual(["d2", "d4", "d5"]);
    expect(freshIds([], 0)).toEqual([]);
  });

  it("are added with the contract's add_object edit", () => {
    const offer = offersOf([box("otherprop", [10.123456, 0, 50.5, 33.339], 0.876543)])[0];
    if (!offer) throw new Error("no offer");
    expect(addObjectEdit(offer, "d7")).toEqual({
      kind: "add_object",
      id: "d7",
      class: "otherprop",
      bbox: [10.12, 0, 50.5, 33.34],
      score: 0.8765,
      source: "detector",
    });
  });
});
