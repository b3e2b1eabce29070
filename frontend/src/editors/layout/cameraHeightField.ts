// The layout bar's camera height: the scale of the whole room, which no photo tells but an
// annotator may know. Shown whenever there is a room, and typed into while editing the layout
// (shown before too, so starting to edit adds no line above the photo).
import { el } from "../../dom";
import { CAMERA_HEIGHT_RANGE_M, type LayoutDraft } from "../../state/layoutDraft";

const HEIGHT_HELP =
  "The camera's height above the floor: the scale of the whole room, which the photo cannot " +
  "tell (the pipeline guesses it from the objects' typical sizes)";

export interface CameraHeightField {
  element: HTMLElement;
  /** `layoutNote`: the stored layout's note (where its scale came from). */
  update(editable: boolean, saving: boolean, layoutNote: string | null | undefined): void;
}

/** `onChange` hears the outcome of a typed height: null when taken, else what was wrong. */
export function cameraHeightField(
  draft: LayoutDraft,
  onChange: (problem: string | null) => void,
): CameraHeightField {
  const input = el("input", {
    testid: "camera-height",
    attrs: {
      type: "number",
      step: "0.01",
      min: String(CAMERA_HEIGHT_RANGE_M[0]),
      max: String(CAMERA_HEIGHT_RANGE_M[1]),
      inputmode: "decimal",
    },
    on: { change: () => setHeight() },
  });
  const element = el(
    "label",
    { className: "camera-height", testid: "camera-height-field" },
    "Camera height ",
    input,
    " m",
  );
  const setHeight = () => {
    if (draft.setCameraHeight(input.valueAsNumber)) {
      onChange(null);
      return;
    }
    const [low, high] = CAMERA_HEIGHT_RANGE_M;
    input.value = draft.cameraHeight.toFixed(2);
    onChange(`The camera's height must be between ${low} and ${high} m.`);
  };
  return {
    element,
    update(editable, saving, layoutNote) {
      element.hidden = !draft.editing && !draft.available;
      const help = draft.editing ? HEIGHT_HELP : `${HEIGHT_HELP}. Edit the layout to change it.`;
      element.title = layoutNote ? `${help}\nThe saved layout: ${layoutNote}` : help;
      input.disabled = !editable || saving || !draft.editing;
      if (document.activeElement !== input) input.value = draft.cameraHeight.toFixed(2);
    },
  };
}
