import type { Camera } from "@holiscene/schema";
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

  it("says where the camera's height came from: measured from the depth's floor", () => {
    const plain = sceneDocument([], [], { revision: 3, size: 64 });
    const camera: Camera = {
      K: [
        [50, 0, 32],
        [0, 50, 32],
        [0, 0, 1],
      ],
      K_source: "given",
      pitch_deg: 10,
      roll_deg: 0,
      height_m: 1.234,
      height_source: "depth",
      note: null,
    };
    const doc = { ...plain, scene: { ...plain.scene, camera } };
    expect(sceneMeta(doc).text).toBe(
      "64×64 · revision 3 · camera 1.23 m high (measured from the depth)",
    );
  });
});
