// The status chip beside an object's supporter menu: how the stored support came about, and,
// while the menus show the model's suggestion instead, what is stored.
import { describe, expect, it } from "vitest";
import type { ShownSupport } from "../state/supportGraph";
import { supportStatus } from "./supportStatus";

const guess = {
  child: "o1",
  parent: "wall",
  type: "behind",
  source: "auto",
  confidence: 0.97,
  author: null,
  pending: false,
} as unknown as ShownSupport;

describe("supportStatus", () => {
  it("says how the stored support came about", () => {
    expect(supportStatus(guess, false, []).text).toBe("auto · 97%");
    expect(supportStatus(undefined, false, []).text).toBe("no supporter");
    const label = { ...guess, source: "manual", author: "anna" } as ShownSupport;
    expect(supportStatus(label, false, [])).toMatchObject({
      text: "manual · anna",
      title: "Set by anna: a label, which retraining learns from",
    });
  });

  it("names the stored supporter while the menus show the model's suggestion", () => {
    const chip = supportStatus(guess, true, []);
    expect(chip.text).toBe("stored: wall");
    expect(chip.title).toMatch(/^Stored: wall · behind; the menus show the model's suggestion/);
    expect(chip.title).toContain("The pipeline's guess, 97% sure");
    expect(supportStatus(undefined, true, []).text).toBe("none stored");
  });
});
