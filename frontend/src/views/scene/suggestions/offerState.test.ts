// A detector run's offers: its boxes at the threshold first, guesses when asked for (the
// suggester's boxes, or the detector's own below its threshold).
import type { SceneObject } from "@holiscene/schema";
import { describe, expect, it } from "vitest";
import type { DetectedBox } from "../../../inference/detectorTensor";
import { OfferState } from "./offerState";
import type { RejectedOffer } from "./rejectedOffers";

const box = (cls: string, bbox: [number, number, number, number], score: number): DetectedBox => ({
  cls,
  bbox,
  score,
  sourceClass: cls,
});

describe("offer state", () => {
  const boxes = [
    box("bed", [100, 100, 400, 400], 0.8),
    box("lamp", [10, 10, 60, 80], 0.2),
    box("picture", [450, 20, 600, 120], 0.12),
    // Faint, and at the bed's place: the same thing, never offered.
    box("sofa", [105, 100, 400, 400], 0.15),
  ];

  it("offers the boxes at the threshold and counts the fainter ones apart", () => {
    const state = new OfferState(() => []);
    state.reset(boxes, 0.3);
    expect(state.open().map((o) => o.cls)).toEqual(["bed"]);
    expect(state.found).toBe(1);
    expect(state.guesses()).toBe(2);
    expect(state.selectedOffer()?.cls).toBe("bed");
  });

  it("shows the fainter boxes when asked, keeping the selection", () => {
    const state = new OfferState(() => []);
    state.reset(boxes, 0.3);
    state.showGuesses();
    expect(state.open().map((o) => o.cls)).toEqual(["bed", "lamp", "picture"]);
    expect(state.found).toBe(4);
    expect(state.guesses()).toBe(0);
    expect(state.selectedOffer()?.cls).toBe("bed");
    // "Accept all" still takes only the boxes at the threshold.
    expect(state.confident().map((o) => o.cls)).toEqual(["bed"]);
  });

  it("moves the selection on to a box at the threshold, never to a fainter one", () => {
    const state = new OfferState(() => []);
    state.reset([...boxes, box("chair", [420, 300, 480, 400], 0.5)], 0.3);
    state.showGuesses();
    state.selected = state.open().find((o) => o.cls === "lamp")?.key ?? null;
    state.reject(state.open().filter((o) => o.cls === "lamp"));
    state.keepSelection();
    expect(state.selectedOffer()?.cls).toBe("bed"); // the best one at the threshold
    state.reject(state.open().filter((o) => o.cls !== "picture"));
    state.keepSelection();
    expect(state.open().map((o) => o.cls)).toEqual(["picture"]);
    expect(state.selectedOffer()).toBeNull(); // only a faint one left: chosen by a click
  });

  it("does not count fainter boxes over the scene's objects or rejected ones", () => {
    const lamp = { id: "o1", class: "lamp", bbox: [10, 12, 60, 80] } as unknown as SceneObject;
    const state = new OfferState(() => [lamp]);
    state.reset(boxes, 0.3);
    expect(state.guesses()).toBe(1);
    state.showGuesses();
    const picture = state.open().find((o) => o.cls === "picture");
    expect(picture).toBeDefined();
    state.reject(picture ? [picture] : []);
    expect(state.open().map((o) => o.cls)).toEqual(["bed"]);
  });

  it("does not offer the boxes of objects people removed, until the rejected ones are asked for", () => {
    const removed: RejectedOffer[] = [{ cls: "bed", bbox: [101, 100, 400, 401] }];
    const state = new OfferState(
      () => [],
      [],
      () => {},
      () => removed,
    );
    state.reset(boxes, 0.3);
    expect(state.open()).toEqual([]);
    expect(state.rejectedHidden()).toBe(1);
    state.forgetRejected();
    expect(state.open().map((o) => o.cls)).toEqual(["bed"]);
    removed.push({ cls: "lamp", bbox: [10, 10, 60, 80] }); // removed after asking: left out
    state.showGuesses();
    expect(state.open().map((o) => o.cls)).toEqual(["bed", "picture"]);
    state.reset(boxes, 0.3); // a new run leaves them all out again
    expect(state.open()).toEqual([]);
  });

  it("leaves boxes rejected on an earlier run out of the next, until asked for again", () => {
    const remembered: string[][] = [];
    const state = new OfferState(
      () => [],
      [{ cls: "lamp", bbox: [12, 10, 60, 82] }],
      (rejected) => remembered.push(rejected.map((r) => r.cls)),
    );
    state.reset(boxes);
    expect(state.open().map((o) => o.cls)).toEqual(["bed", "picture"]);
    expect(state.rejectedHidden()).toBe(1);
    const bed = state.open()[0];
    state.reject(bed ? [bed] : []);
    expect(remembered).toEqual([["lamp", "bed"]]);
    state.reset(boxes); // "Detect objects" again
    expect(state.open().map((o) => o.cls)).toEqual(["picture"]);
    expect(state.rejectedHidden()).toBe(2);
    state.forgetRejected();
    expect(remembered.at(-1)).toEqual([]);
    expect(state.open().map((o) => o.cls)).toEqual(["bed", "lamp", "picture"]);
    expect(state.rejectedHidden()).toBe(0);
  });

  it("takes the suggester's boxes as the guesses once it has run, the suggestions standing", () => {
    const state = new OfferState(() => []);
    state.reset(boxes, 0.3, true);
    expect(state.guesses()).toBe(0); // the suggester is still running: no button yet
    state.setGuesses([
      // A surer guess at the bed's place: the same thing, the suggestion stands.
      box("sofa", [100, 102, 400, 400], 0.9),
      box("lamp", [10, 10, 60, 80], 0.6),
      box("night_stand", [420, 300, 480, 400], 0.4),
    ]);
    expect(state.guesses()).toBe(2);
    expect(state.open().map((o) => o.cls)).toEqual(["bed"]);
    state.showGuesses();
    const open = state.open();
    expect(open.map((o) => [o.cls, o.faint])).toEqual([
      ["bed", false],
      ["lamp", true],
      ["night_stand", true],
    ]);
    expect(new Set(open.map((o) => o.key)).size).toBe(3);
    expect(state.confident().map((o) => o.cls)).toEqual(["bed"]);
    expect(state.found).toBe(4);
  });

  it("falls back to the detector's own fainter boxes without a suggester", () => {
    const state = new OfferState(() => []);
    state.reset(boxes, 0.3, true);
    state.setGuesses(null);
    expect(state.guesses()).toBe(2);
    state.showGuesses();
    expect(state.open().map((o) => o.cls)).toEqual(["bed", "lamp", "picture"]);
  });

  it("has nothing fainter without a threshold", () => {
    const state = new OfferState(() => []);
    state.reset(boxes);
    expect(state.guesses()).toBe(0);
    expect(state.open()).toHaveLength(3);
  });
});
