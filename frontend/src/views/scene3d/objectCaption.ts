// The line over the 3D view naming the object under the pointer (or the selected one): which
// object it is, and its 3D box's size in metres, so a reviewer can tell a lamp 2 m tall or a
// bed 40 cm long without opening the viser viewer.
import type { SceneObject } from "@holiscene/schema";
import { percentText } from "../../dom";
import { objectClassText } from "../../state/classNames";

const metres = (value: number) => value.toFixed(2);

/** "o3 books · 3D box 0.50 × 0.23 × 0.21 m (depth × height × width) · 87% likely right
 * (box refiner)" */
export function objectCaption(
  object: Pick<SceneObject, "id" | "class" | "box_3d" | "box_3d_confidence"> & {
    source_class?: string | null;
  },
): string {
  // The class as the object list writes it ("otherprop (clock)": the detector's own name too).
  const name = `${object.id} ${objectClassText(object)}`;
  const box = object.box_3d;
  if (!box) return `${name} · no 3D box`;
  const size = box.size.map(metres).join(" × ");
  const sure =
    typeof object.box_3d_confidence === "number"
      ? ` · ${percentText(object.box_3d_confidence)} likely right (box refiner)`
      : "";
  return `${name} · 3D box ${size} m (depth × height × width)${sure}`;
}
