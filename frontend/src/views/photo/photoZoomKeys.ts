// The photo's zoom keys: + and - zoom about the middle, 0 fits the whole photo, and Space held
// over the photo turns a drag into a pan.
import { registerShortcut } from "../../shortcuts";

export interface ZoomKeyActions {
  zoomIn(): void;
  zoomOut(): void;
  fit(): void;
  /** The pointer is over the photo (elsewhere Space keeps scrolling and pressing buttons). */
  over(): boolean;
  /** Space went down over the photo. */
  holdSpace(): void;
}

/** Register the keys; returns the function that removes them. */
export function photoZoomKeys(actions: ZoomKeyActions): () => void {
  const scope = "Photo";
  const removers = [
    registerShortcut({
      keys: ["+", "="],
      description: "Zoom the photo in (the wheel zooms about the pointer)",
      scope,
      run: actions.zoomIn,
    }),
    registerShortcut({
      keys: "-",
      description: "Zoom the photo out",
      scope,
      run: actions.zoomOut,
    }),
    registerShortcut({
      keys: "0",
      description: "Fit the whole photo",
      scope,
      run: actions.fit,
    }),
    registerShortcut({
      keys: "Space",
      description: "Hold over the photo and drag to pan (or drag with the middle button)",
      scope,
      enabled: actions.over,
      run: actions.holdSpace,
    }),
  ];
  return () => {
    for (const remove of removers) remove();
  };
}
