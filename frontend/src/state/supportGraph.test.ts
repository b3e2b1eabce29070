// Which stored supports are shown as doubtful: the pipeline's guesses under even odds only.
import { describe, expect, it } from "vitest";
import { implausibleBelow, isDoubtfulSupport, type ShownSupport } from "./supportGraph";

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

describe("a supporter from below beside its object", () => {
  const lamp = { id: "o1", bbox: [100, 50, 140, 120] as [number, number, number, number] };
  const table = { id: "o2", bbox: [80, 110, 260, 200] as [number, number, number, number] };
  const dresser = { id: "o3", bbox: [300, 100, 420, 220] as [number, number, number, number] };

  it("is questioned when the two boxes share no width", () => {
    expect(implausibleBelow(lamp, dresser, "below")).toBe(
      "o3 is beside o1 on the photo, not under it: is it the right supporter?",
    );
  });

  it("is not questioned under the object, from behind, or on the floor", () => {
    expect(implausibleBelow(lamp, table, "below")).toBeNull();
    expect(implausibleBelow(lamp, dresser, "behind")).toBeNull();
    expect(implausibleBelow(lamp, undefined, "below")).toBeNull();
  });
});
