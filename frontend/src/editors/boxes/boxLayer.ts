// What the box tool draws over the photo: boxes sent and not yet in a revision, the selected
// (or dragged) box with its 8 handles, and the box being drawn.
import type { SceneObject } from "@holiscene/schema";
import { svgEl } from "../../dom";
import { type Box, HANDLES, handlePoint } from "../boxGeometry";

/** Handle size on the screen, pixels, on a box large enough for it. */
export const HANDLE_PX = 9;
/** The smallest handle drawn, screen pixels. */
const MIN_HANDLE_PX = 3;

/**
 * How far from a handle a press still grips it, in photo pixels (the handle is drawn that
 * wide). On a small box the handles shrink to a quarter of its shorter side, so that at least
 * half of it is left to move it by: full-size handles covered a small box, and a press meant
 * to move it resized it.
 */
export function handleReach(box: readonly number[], pixelSize: number): number {
  const shorter = Math.min((box[2] ?? 0) - (box[0] ?? 0), (box[3] ?? 0) - (box[1] ?? 0));
  const screen = Math.max(MIN_HANDLE_PX, Math.min(HANDLE_PX, shorter / pixelSize / 4));
  return screen * pixelSize;
}

export interface BoxLayerState {
  /** Boxes sent and not yet in a revision. */
  sending: Iterable<Box>;
  selected: SceneObject | null | undefined;
  /** The box being moved or resized, if one is. */
  editing: Box | null;
  /** The new box being drawn, if one is. */
  drawing: Box | null;
  /** Photo pixels per screen pixel. */
  pixelSize: number;
}

function rect(box: readonly number[], className: string, px: number, testid?: string) {
  return svgEl("rect", {
    class: className,
    "data-testid": testid,
    x: box[0],
    y: box[1],
    width: (box[2] ?? 0) - (box[0] ?? 0),
    height: (box[3] ?? 0) - (box[1] ?? 0),
    "stroke-width": px * 2,
  });
}

export function drawBoxLayer(layer: SVGGElement, state: BoxLayerState): void {
  const { pixelSize: px, selected, editing, drawing } = state;
  const nodes: SVGElement[] = [];
  for (const box of state.sending) nodes.push(rect(box, "box-tool-pending", px));
  const box = editing ?? selected?.bbox;
  if (box && (editing || selected)) {
    nodes.push(rect(box, "box-tool-selected", px, "box-tool-selected"));
    const size = handleReach(box, px);
    for (const handle of HANDLES) {
      const [x, y] = handlePoint(box, handle);
      nodes.push(
        svgEl("rect", {
          class: "box-tool-handle",
          "data-testid": "box-handle",
          "data-handle": handle,
          x: x - size / 2,
          y: y - size / 2,
          width: size,
          height: size,
          "stroke-width": px * 1.2,
        }),
      );
    }
  }
  if (drawing) nodes.push(rect(drawing, "box-tool-drawing", px, "box-tool-drawing"));
  layer.replaceChildren(...nodes);
}
