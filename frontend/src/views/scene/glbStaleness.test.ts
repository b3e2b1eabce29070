// The Download menu says what the 3D scene file lacks of the scene now.
import type { SceneDocument } from "@holiscene/schema";
import { describe, expect, it } from "vitest";
import { sceneDocument, sceneObject } from "../../testing/sceneDocuments";
import { glbLacks, glbStaleness } from "./glbStaleness";

const at = (doc: SceneDocument, revision: number): SceneDocument => ({ ...doc, revision });

describe("the 3D scene file's age", () => {
  const bed = sceneObject("o0", "bed", [0, 0, 50, 50]);
  const chair = sceneObject("o1", "chair", [60, 60, 80, 90]);
  const made = at(sceneDocument([bed, chair]), 2);

  it("names what was added, removed or redrawn since it was made", () => {
    const lamp = sceneObject("d1", "lamp", [5, 5, 9, 9]);
    const moved = { ...chair, bbox: [61, 60, 80, 90] } as typeof chair;
    const now = at(sceneDocument([moved, lamp]), 5);
    expect(glbStaleness(made, now)).toBe(
      'made at revision 2; since then 1 object added, 1 removed, 1 changed: "Re-place objects" ' +
        "in the 3D panel brings it up to date",
    );
  });

  it("names no remedy the page cannot offer: a submitted or accepted scene is not re-placed", () => {
    const now = at(sceneDocument([bed]), 4);
    expect(glbStaleness(made, now, false)).toBe(
      "made at revision 2; since then 1 removed: it can be re-placed only while the scene is " +
        "being annotated",
    );
    expect(glbLacks(made.scene, now.scene)).toBe("1 removed");
  });

  it("says nothing when only supports changed (the file has no supports)", () => {
    expect(glbStaleness(made, at(sceneDocument([bed, chair]), 3))).toBeNull();
    expect(glbLacks(made.scene, at(sceneDocument([bed, chair]), 3).scene)).toBe("");
  });
});
