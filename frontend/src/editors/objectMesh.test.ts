// The object list's mesh badge: which of the pipeline's shape stages made the object's mesh.
import { describe, expect, it } from "vitest";
import { objectMesh } from "./objectMesh";

describe("object mesh", () => {
  it("shows nothing for an object without a mesh", () => {
    expect(objectMesh({ mesh: null })).toBeNull();
  });

  it("names each source of a mesh", () => {
    const library = objectMesh({
      mesh: { class: "chair", file: null, library: "builtin", seed: 3 },
    });
    expect(library).toMatchObject({ kind: "builtin", text: "mesh: library" });
    expect(library?.title).toContain("chair");
    expect(library?.title).toContain("variant 3");
    const learned = objectMesh({
      mesh: { class: "sofa", file: null, library: "learned", seed: null },
    });
    expect(learned).toMatchObject({ kind: "learned", text: "mesh: learned" });
    expect(learned?.title).toContain("mesh network");
    const completed = objectMesh({
      mesh: { class: "table", file: null, library: "completion", seed: null },
    });
    expect(completed?.text).toBe("mesh: from depth");
    const file = objectMesh({
      mesh: { class: "lamp", file: "lamp.glb", library: "user", seed: null },
    });
    expect(file?.title).toContain("lamp.glb");
  });
});
