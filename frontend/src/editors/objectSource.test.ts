// The object list's source badge: given, detector with its score, person, and edited.
import { describe, expect, it } from "vitest";
import { objectSource } from "./objectSource";

describe("object source", () => {
  it("names the source and the detector's score", () => {
    expect(objectSource({ source: "given", score: null, set_by_person: [] }).text).toBe("given");
    const detected = objectSource({ source: "detector", score: 0.874, set_by_person: [] });
    expect(detected).toMatchObject({ kind: "detector", text: "detector 87%" });
    expect(detected.title).toContain("score 87%");
    expect(
      objectSource({ source: "manual", score: null, set_by_person: ["object"] }),
    ).toMatchObject({ kind: "person", text: "by hand" });
  });

  it("says when a person accepted or changed a detected object", () => {
    const accepted = objectSource({ source: "detector", score: 0.5, set_by_person: ["object"] });
    expect(accepted.text).toBe("detector 50%");
    expect(accepted.title).toContain("accepted by a person");
    const edited = objectSource({
      source: "detector",
      score: 0.5,
      set_by_person: ["object", "class", "mask"],
    });
    expect(edited.text).toBe("detector 50% · edited");
    expect(edited.title).toContain("class, mask");
  });

  it("shows nothing for old scenes without sources, unless edited", () => {
    expect(objectSource({ source: null, score: null, set_by_person: [] }).text).toBe("");
    expect(objectSource({ source: null, score: null, set_by_person: ["bbox"] }).text).toBe(
      "edited",
    );
  });
});
