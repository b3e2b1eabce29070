import { describe, expect, it } from "vitest";
import { addedObjectsText } from "./addOffers";

const added = (...classes: string[]) => classes.map((cls, i) => ({ id: `d${i + 1}`, class: cls }));

describe("addedObjectsText", () => {
  it("names a few new objects one by one", () => {
    expect(addedObjectsText(added("chair", "lamp"))).toBe("d1 (chair), d2 (lamp)");
  });

  it("counts many per class, the commonest first, so a bulk accept stays one short line", () => {
    const text = addedObjectsText(added("sofa", "chair", "chair", "table", "chair", "sofa"));
    expect(text).toBe("6 objects (3 chair, 2 sofa, 1 table)");
  });
});
