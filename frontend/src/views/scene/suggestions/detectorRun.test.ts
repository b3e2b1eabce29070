import { describe, expect, it } from "vitest";
import { type DetectorRun, foundText } from "./detectorRun";

const run = (over: Partial<DetectorRun> = {}): DetectorRun => ({
  seen: [],
  loadMs: 1500,
  runMs: 600,
  flat: false,
  detector: "COCO PicoDet-S 416 (LCNet), converted",
  ...over,
});

describe("foundText", () => {
  it("says what was suggested, how fast and by which detector", () => {
    expect(foundText(5, 5, run())).toBe(
      "5 objects suggested in 0.6 s by COCO PicoDet-S 416 (LCNet), converted " +
        "(loading it took 1.5 s): click a box, then Accept or Reject.",
    );
    expect(foundText(3, 0, run({ loadMs: 10 }))).toBe(
      "3 boxes found in 0.6 s by COCO PicoDet-S 416 (LCNet), converted, all labelled already.",
    );
  });

  it("says when boxes rejected before are left out", () => {
    expect(foundText(4, 2, run({ loadMs: 10 }), 2)).toBe(
      "2 objects suggested in 0.6 s by COCO PicoDet-S 416 (LCNet), converted " +
        "(2 rejected before left out): click a box, then Accept or Reject.",
    );
    expect(foundText(3, 0, run({ loadMs: 10 }), 1)).toMatch(
      /, all labelled or rejected already \(1 rejected before left out\)\.$/,
    );
  });

  it("says why nothing was looked for in a flat photo", () => {
    expect(foundText(0, 0, run({ flat: true }))).toMatch(/one flat colour/);
  });
});
