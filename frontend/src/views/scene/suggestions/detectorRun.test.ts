import { describe, expect, it } from "vitest";
import { type DetectorRun, foundText, shortDetectorName } from "./detectorRun";

const run = (over: Partial<DetectorRun> = {}): DetectorRun => ({
  seen: [],
  loadMs: 1500,
  runMs: 600,
  flat: false,
  detector: "COCO PicoDet-S 416 (LCNet), converted",
  pixels: { width: 1, height: 1, data: new Uint8ClampedArray(4) },
  ...over,
});

describe("foundText", () => {
  it("says what was suggested, how fast and by which detector", () => {
    expect(foundText(5, 5, run())).toBe(
      "5 objects suggested in 0.6 s by COCO PicoDet-S 416: click a box, then Accept or Reject.",
    );
    expect(foundText(3, 0, run({ loadMs: 10 }))).toBe(
      "Nothing new: the 3 boxes found are on objects labelled already, in 0.6 s by COCO " +
        "PicoDet-S 416.",
    );
  });

  it("says when boxes rejected before are left out", () => {
    expect(foundText(4, 2, run({ loadMs: 10 }), 2)).toBe(
      "2 objects suggested (2 rejected before left out) in 0.6 s by COCO PicoDet-S 416: " +
        "click a box, then Accept or Reject.",
    );
    expect(foundText(1, 0, run({ loadMs: 10 }), 1)).toMatch(
      /^Nothing new: the box found is on an object labelled or rejected already \(1 rejected before left out\), in 0.6 s/,
    );
  });

  it("names a detector up to its first comma or bracket", () => {
    expect(shortDetectorName("COCO PicoDet-S 416 (LCNet), converted")).toBe("COCO PicoDet-S 416");
    expect(shortDetectorName("NYU-40 head, fine-tuned")).toBe("NYU-40 head");
    expect(shortDetectorName("plain")).toBe("plain");
  });

  it("says why nothing was looked for in a flat photo", () => {
    expect(foundText(0, 0, run({ flat: true }))).toMatch(/one flat colour/);
  });
});
