// The scene page's header line: the photo's size, the revision, whether depth came with the
// photo, and the camera's height (the scale of the whole scene) with where it came from.
import type { Camera, SceneDocument } from "@holiscene/schema";

/** How the camera's height was found, in words. */
const HEIGHT_SOURCES: Record<NonNullable<Camera["height_source"]>, string> = {
  prior: "a prior",
  estimated: "estimated",
  manual: "set by hand",
  ground_truth: "ground truth",
  depth: "measured from the depth",
};

/** The line's text, and its tooltip (the layout's note says more about the scale). */
export function sceneMeta(doc: SceneDocument): { text: string; title: string } {
  const { image, camera, layout } = doc.scene;
  const parts = [`${image.width}×${image.height}`, `revision ${doc.revision}`];
  if (doc.scene.depth) parts.push("with depth");
  if (camera?.height_m != null) {
    const source = HEIGHT_SOURCES[camera.height_source ?? "estimated"];
    parts.push(`camera ${camera.height_m.toFixed(2)} m high (${source})`);
  }
  return { text: parts.join(" · "), title: layout?.note ?? "" };
}
