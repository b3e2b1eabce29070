import type { SceneDocument } from "@holiscene/schema";
import { describe, expect, it } from "vitest";
import { sceneDocument } from "../../testing/sceneDocuments";
import { mayHaveGlb } from "./viewportObjects";

const withStages = (names: string[]): SceneDocument => {
  const doc = sceneDocument([]);
  const stages = names.map((name) => ({ name, seconds: 0, note: null, warning: false }));
  return { ...doc, scene: { ...doc.scene, stages } };
};

describe("whether the 3D view asks for scene.glb", () => {
  it("does once the pipeline's scene_mesh stage made the revision", () => {
    expect(mayHaveGlb(withStages(["placement", "shapes_fit", "scene_mesh"]))).toBe(true);
  });

  it("does not for a scene the pipeline has not run on (no 404 in the console)", () => {
    expect(mayHaveGlb(sceneDocument([]))).toBe(false);
    expect(mayHaveGlb(withStages(["objects_from_detections", "masks_grabcut"]))).toBe(false);
  });
});
