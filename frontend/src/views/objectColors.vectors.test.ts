// The object-colour vectors the backend writes (shared_schema/vectors/object_colours.json):
// the viser viewer paints each object as the scene page colours its mask.
import { describe, expect, it } from "vitest";
import vectorsText from "../../../shared_schema/vectors/object_colours.json?raw";
import { objectColours } from "./objectColors";

interface Case {
  ids: string[];
  colours: [number, number, number][];
}

const cases = (JSON.parse(vectorsText) as { cases: Case[] }).cases;

describe("object colours shared with the viewer", () => {
  it("has vectors to check", () => {
    expect(cases.length).toBeGreaterThan(3);
  });

  it.each(cases.map((c) => [c.ids.slice(0, 3).join(" "), c] as const))(
    "gives %s… the viewer's colours",
    (_, { ids, colours }) => {
      const mine = objectColours(ids.map((id) => ({ id })));
      expect(ids.map((id) => mine.get(id))).toEqual(colours);
    },
  );
});
