// The class picker's hints: the classes of the detector's boxes at a box, best first.
import { describe, expect, it } from "vitest";
import { classHints, HINT_SCORE, likelyClasses, MAX_HINTS } from "./classHints";

const seen = (cls: string, score: number, bbox: [number, number, number, number]) => ({
  cls,
  score,
  bbox,
  sourceClass: cls,
});

describe("likelyClasses", () => {
  const box: [number, number, number, number] = [100, 100, 200, 200];

  it("lists the classes of boxes at the same place, best score first, each once", () => {
    const hints = likelyClasses(box, [
      seen("box", 0.53, [100, 100, 200, 200]),
      seen("books", 0.25, [102, 98, 198, 203]),
      seen("books", 0.4, [105, 105, 205, 205]),
    ]);
    expect(hints).toEqual([
      { cls: "box", score: 0.53 },
      { cls: "books", score: 0.4 },
    ]);
  });

  it("leaves out boxes elsewhere (IoU below a half) and faint ones", () => {
    expect(likelyClasses(box, [seen("lamp", 0.9, [150, 150, 250, 250])])).toEqual([]);
    expect(likelyClasses(box, [seen("lamp", HINT_SCORE / 2, box)])).toEqual([]);
  });

  it("hints at most a few classes, so the scene's own classes stay among the first lines", () => {
    const many = ["chair", "sofa", "table", "desk", "lamp"].map((c, i) =>
      seen(c, 0.5 - i / 20, box),
    );
    expect(likelyClasses(box, many).map((h) => h.cls)).toEqual(
      ["chair", "sofa", "table", "desk", "lamp"].slice(0, MAX_HINTS),
    );
  });

  it("keeps each scene's boxes apart; a scene the detector has not seen has no hints", () => {
    classHints.set("aaaaaaaaaaaa", [seen("lamp", 0.2, box), seen("desk", 0.01, box)]);
    expect(classHints.at("aaaaaaaaaaaa", box)).toEqual([{ cls: "lamp", score: 0.2 }]);
    expect(classHints.at("bbbbbbbbbbbb", box)).toEqual([]);
  });

  it("adds the suggester's boxes to the detector's run; a new run starts over", () => {
    classHints.set("cccccccccccc", [seen("table", 0.5, box)]);
    classHints.add("cccccccccccc", [seen("desk", 0.6, box), seen("lamp", 0.05, box)]);
    expect(classHints.at("cccccccccccc", box).map((h) => h.cls)).toEqual(["desk", "table"]);
    classHints.set("cccccccccccc", [seen("chair", 0.4, box)]);
    expect(classHints.at("cccccccccccc", box).map((h) => h.cls)).toEqual(["chair"]);
  });
});
