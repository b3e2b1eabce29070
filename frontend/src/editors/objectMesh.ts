// Where an object's 3D mesh comes from, for the object list: a reviewer who sees a strange shape
// in the 3D view can tell the furniture library's fit from the mesh network's deformed template
// or a mesh completed from depth points (MeshRef.library). Objects without a mesh show nothing.
import type { SceneObject } from "@holiscene/schema";
import { classText } from "../state/classNames";

export interface MeshText {
  /** Short, for the badge: "mesh: learned". */
  text: string;
  /** Longer, for the tooltip. */
  title: string;
  kind: "builtin" | "user" | "completion" | "learned";
}

export function objectMesh({ mesh }: Pick<SceneObject, "mesh">): MeshText | null {
  if (!mesh) return null;
  switch (mesh.library) {
    case "builtin":
      return {
        kind: "builtin",
        text: "mesh: library",
        title:
          `A ${classText(mesh.class)} from the built-in furniture library` +
          (mesh.seed === null ? "" : ` (variant ${mesh.seed})`) +
          ", chosen to fit the mask and stretched to the 3D box",
      };
    case "user":
      return {
        kind: "user",
        text: "mesh: file",
        title: `A mesh file${mesh.file ? ` (${mesh.file})` : ""}, fitted to the 3D box`,
      };
    case "completion":
      return {
        kind: "completion",
        text: "mesh: from depth",
        title:
          "Completed by the shape-completion network from the object's depth points: a " +
          "surface meshed from points, so it is rough and has holes where the depth saw little",
      };
    case "learned":
      return {
        kind: "learned",
        text: "mesh: learned",
        title: `The ${classText(mesh.class)} template deformed by the mesh network to match the mask`,
      };
  }
}
