// The mask tools on the photo: Brush (adds to the selected object's mask), Eraser (takes
// away), Polygon (click points; Enter or a click on the first point closes it; Shift
// subtracts) and Refine (foreground strokes, Alt for background, cut by the server's GrabCut).
// What a tool draws is shown at once in place of the stored mask (maskPreview.ts); when the
// pointer is released or the polygon closes, the new mask goes to the server as one set_mask
// edit (objectEditor.apply: one revision, undoable). With no object selected, a press on an
// object selects it, and a press elsewhere says what to do.
import { registerShortcut } from "../shortcuts";
import { LARGER_KEY, SMALLER_KEY } from "./masks/brushSize";
import { MaskDrawing } from "./masks/maskDrawing";
import { POLYGON_KEY, polygonTool } from "./masks/polygonTool";
import { REFINE_KEY, refineTool } from "./masks/refineTool";
import { strokeTool } from "./masks/strokeTool";
import type { PhotoTool, PhotoTools } from "./photoTools";
import "./maskTools.css";

// One tool per file in masks/ (strokeTool: Brush and Eraser, polygonTool, refineTool), with
// what they share in maskDrawing (preview, brush size, status, saving) and brushSize.
export { LARGER_KEY, POLYGON_KEY, REFINE_KEY, SMALLER_KEY };
export const BRUSH_KEY = "P";
export const ERASER_KEY = "Shift+P";
const SCOPE = "Mask tools";

/** Mount the four tools on the photo's toolbar; returns the function that removes them. */
export function mountMaskTools(tools: PhotoTools): () => void {
  const { host } = tools;
  const { session } = host;
  const drawing = new MaskDrawing(host);
  const { brush, live, preview } = drawing;
  const brushTool = strokeTool(drawing, {
    id: "brush",
    label: "Brush",
    key: BRUSH_KEY,
    value: 1,
    description: "Brush: paint the selected object's mask",
  });
  const eraserTool = strokeTool(drawing, {
    id: "eraser",
    label: "Eraser",
    key: ERASER_KEY,
    value: 0,
    description: "Eraser: take pixels out of the selected object's mask",
  });
  const polygon = polygonTool(drawing);
  const refine = refineTool(drawing);
  const maskTools: PhotoTool[] = [brushTool, eraserTool, polygon.tool, refine];
  const removers = maskTools.map((tool) => tools.add(tool));

  const sized = () => [brushTool, eraserTool, refine].includes(tools.active) && session.editable;
  const drafting = () => tools.active === polygon.tool && polygon.drafting();
  removers.push(
    registerShortcut({
      keys: SMALLER_KEY,
      description: "Smaller brush (Brush, Eraser, Refine)",
      scope: SCOPE,
      run: () => brush.step(false),
      enabled: sized,
    }),
    registerShortcut({
      keys: LARGER_KEY,
      description: "Larger brush (Brush, Eraser, Refine)",
      scope: SCOPE,
      run: () => brush.step(true),
      enabled: sized,
    }),
    registerShortcut({
      keys: "Enter",
      description: "Close the polygon being drawn",
      scope: SCOPE,
      run: polygon.close,
      enabled: () => drafting() && polygon.points() >= 3,
    }),
    registerShortcut({
      keys: "Backspace",
      description: "Take back the polygon's last point (while drawing one)",
      scope: SCOPE,
      run: polygon.dropPoint,
      enabled: drafting,
    }),
  );
  const stopSelect = session.subscribe((change) => {
    // A revision adopted while a newer drawing is shown must not show through it.
    if (change === "document") preview.keepStoredHidden();
    if (change === "select" && maskTools.includes(tools.active)) drawing.describeTarget();
  });
  const hideCursor = () => drawing.placeCursor(null);
  const replace = () => {
    live.place();
    polygon.redraw();
  };
  const stopView = host.onView(replace);
  // The photo's size follows its panel (window, side panels), not only the window.
  const resized = new ResizeObserver(replace);
  resized.observe(host.svg);
  host.svg.addEventListener("pointerleave", hideCursor);

  return () => {
    stopSelect();
    host.svg.removeEventListener("pointerleave", hideCursor);
    resized.disconnect();
    for (const remove of removers) remove();
    preview.hide();
    stopView();
    live.dispose();
  };
}
