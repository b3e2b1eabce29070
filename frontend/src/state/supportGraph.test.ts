// Which stored supports are shown as doubtful: the pipeline's guesses under even odds only.
import { describe, expect, it } from "vitest";
import { isDoubtfulSupport, type ShownSupport } from "./supportGraph";

const shown = (over: Partial<ShownSupport>): ShownSupport => ({
  child: "o1",
  parent: "o0",
  type: "below",
  saved: null,
  pending: false,
  source: "auto",
  author: null,
  time: null,
  confidence: 0.42,
  ...over,
});

describe("doubtful supports", () => {
  it("are the pipeline's guesses under 50%", () => {
    expect(isDoubtfulSupport(shown({}))).toBe(true);
    expect(isDoubtfulSupport(shown({ confidence: 0.5 }))).toBe(false);
    expect(isDoubtfulSupport(shown({ confidence: null }))).toBe(false);
  });

  it("are never a person's choice, nor a missing supporter", () => {
    expect(isDoubtfulSupport(shown({ source: "manual" }))).toBe(false);
    expect(isDoubtfulSupport(undefined)).toBe(false);
    expect(isDoubtfulSupport(null)).toBe(false);
  });
});
