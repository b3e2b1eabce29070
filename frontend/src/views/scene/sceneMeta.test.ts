import { describe, expect, it } from "vitest";
import { sceneDocument } from "../../testing/sceneDocuments";
import { sceneMeta } from "./sceneMeta";

describe("sceneMeta", () => {
  it("says when depth came with the photo, and only then", () => {
    const plain = sceneDocument([], [], { revision: 2, size: 64 });
    expect(sceneMeta(plain).text).toBe("64×64 · revision 2");
    const withDepth = {
      ...plain,
      scene: { ...plain.scene, depth: { file: "depth.png", metres_per_unit: 0.001 } },
    };
    expect(sceneMeta(withDepth).text).toBe("64×64 · revision 2 · with depth");
  });
});
