import type { SceneDocument } from "@holiscene/schema";
import { describe, expect, it } from "vitest";
import { sceneDocument, sceneObject } from "../../testing/sceneDocuments";
import { mayHaveGlb, missingSceneText } from "./viewportObjects";

const withStages = (names: string[], doc = sceneDocument([])): SceneDocument => {
  const stages = names.map((name) => ({
    name,
    seconds: 0,
    note: null,
    warning: false,
    model: null,
  }));
  return { ...doc, scene: { ...doc.scene, stages } };
};

describe("whether the 3D view asks for scene.glb", () => {
  it("does once the pipeline's scene_mesh stage made the revision with something in it", () => {
    const ran = withStages(["placement", "shapes_fit", "scene_mesh"]);
    const withScene = (over: Record<string, unknown>) =>
      ({ ...ran, scene: { ...ran.scene, ...over } }) as SceneDocument;
    const corner: [number, number, number] = [0, 0, 1];
    expect(mayHaveGlb(withScene({ layout: { corners_3d: Array(8).fill(corner) } }))).toBe(true);
    expect(mayHaveGlb(withScene({ camera: { height_m: 1.5, pitch_deg: -10 } }))).toBe(true);
    const placed = { ...sceneObject("o0"), box_3d: { centre: [0, 0, 3] } };
    expect(mayHaveGlb(withScene({ objects: [placed] }))).toBe(true);
    // A photo of one flat colour: no object placed, no room, no floor; the stage wrote no GLB.
    expect(mayHaveGlb(ran)).toBe(false);
    expect(mayHaveGlb(withScene({ objects: [sceneObject("o0")], camera: { height_m: 1.5 } }))).toBe(
      false,
    );
  });

  it("does not for a scene the pipeline has not run on (no 404 in the console)", () => {
    expect(mayHaveGlb(sceneDocument([]))).toBe(false);
    expect(mayHaveGlb(withStages(["objects_from_detections", "masks_grabcut"]))).toBe(false);
  });
});

describe("what the 3D view says without a 3D scene", () => {
  it("tells a scene the pipeline has not run on, one without objects, and one it placed none of", () => {
    expect(missingSceneText(sceneDocument([]))).toMatch(/once the pipeline has run/);
    expect(missingSceneText(withStages(["scene_mesh"]))).toMatch(/^No objects to show in 3D/);
    const chair = sceneObject("o0", "chair");
    expect(missingSceneText(withStages(["scene_mesh"], sceneDocument([chair])))).toMatch(
      /placed no object in 3D/,
    );
  });
});
