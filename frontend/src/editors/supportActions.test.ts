// The parts of the room hold objects up one way only: the floor from below, a wall and the
// ceiling from behind. T does not flip such an edge, and accepting a guess stores the right
// type even where the guess names the other one.
import type { SupportRelation } from "@holiscene/schema";
import { describe, expect, it } from "vitest";
import { MemoryStorage } from "../testing/memoryStorage";
import { sceneDocument, sceneObject, sessionOn } from "../testing/sceneDocuments";
import { supportRelation } from "../testing/supports";
import { acceptAll, acceptEdge, flipType, setSupporter } from "./supportActions";

const session = (supports: SupportRelation[]) =>
  sessionOn(
    sceneDocument(
      ["o0", "o1", "o2"].map((id, i) => sceneObject(id, "box", [i * 10, 0, i * 10 + 8, 8])),
      supports,
      { revision: 2 },
    ),
    new MemoryStorage(),
  );

describe("support types of the room's parts", () => {
  it("T flips an edge between objects, not one to the floor or a wall", () => {
    const s = session([supportRelation("o0", "floor"), supportRelation("o1", "o0")]);
    expect(flipType(s, "o0")).toBe("The floor holds o0 up from below only.");
    expect(s.pending).toHaveLength(0);
    expect(flipType(s, "o1")).toBeNull();
    expect(s.shown().get("o1")?.type).toBe("behind");
    setSupporter(s, "o1", "wall");
    expect(s.shown().get("o1")?.type).toBe("behind");
    expect(flipType(s, "o1")).toBe("The wall holds o1 up from behind only.");
  });

  it("accepting a guess of the floor from behind stores it from below", () => {
    const odd = { ...supportRelation("o0", "floor"), type: "behind" as const };
    const s = session([odd, { ...supportRelation("o1", "ceiling"), type: "below" as const }]);
    acceptEdge(s, "o0");
    expect(s.pending).toEqual([
      { kind: "set_support", child: "o0", parent: "floor", type: "below" },
    ]);
    acceptAll(s);
    expect(s.pending).toContainEqual({
      kind: "set_support",
      child: "o1",
      parent: "ceiling",
      type: "behind",
    });
  });

  it("a supporter picked takes the room part's type, or keeps the type between objects", () => {
    const s = session([{ ...supportRelation("o1", "o0"), type: "behind" as const }]);
    setSupporter(s, "o1", "o2");
    expect(s.shown().get("o1")?.type).toBe("behind");
    setSupporter(s, "o1", "floor");
    expect(s.shown().get("o1")?.type).toBe("below");
  });
});
