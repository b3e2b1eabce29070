// One room corner's handle on the photo (layoutLayer.ts): a circle (larger on the drawing's
// edge, for a corner out of sight, with an arrowhead pointing at it), its tooltip and the data
// end-to-end tests read.
import { svgEl } from "../../dom";
import type { Point2 } from "../../geometry/camera";
import type { Frame } from "./arrowGeometry";
import { offPhotoText, type PlacedHandle } from "./cornerHandles";

export const fmt = (p: Point2) => `${p[0].toFixed(1)} ${p[1].toFixed(1)}`;

export interface HandleStyle {
  frame: Frame;
  /** The handles' line width, and their radius (on the drawing's edge: `clampedRadius`). */
  strokeWidth: number;
  radius: number;
  clampedRadius: number;
}

function handleTitle(h: PlacedHandle, frame: Frame): string {
  const name = `Room corner ${h.index} (${h.index < 4 ? "floor" : "ceiling"})`;
  const where = h.clamped ? `, ${offPhotoText(h.corner, frame.width, frame.height)}` : "";
  const how = h.pinned ? "" : "; placed by the fitted room until you drag it";
  const action = h.clamped ? "drag to move it by as much as you drag" : "drag";
  return `${name}${where}${how}: ${action}`;
}

export function handleNode(h: PlacedHandle, style: HandleStyle, dragging: boolean): SVGGElement {
  const { radius, clampedRadius } = style;
  const classes = [
    "layout-handle",
    h.pinned ? "" : "is-free",
    h.clamped ? "is-clamped" : "",
    dragging ? "is-dragging" : "",
  ];
  const r = h.clamped ? clampedRadius : radius;
  const parts: SVGElement[] = [
    svgEl("title", {}, handleTitle(h, style.frame)),
    svgEl("circle", { r: radius * 1.8, class: "layout-handle-hit" }),
    svgEl("circle", { r, "stroke-width": style.strokeWidth * 0.8 }),
  ];
  if (h.direction) {
    // An arrowhead inside the handle, pointing at the corner off the photo.
    const [dx, dy] = h.direction;
    const tip: Point2 = [dx * r * 0.8, dy * r * 0.8];
    const base: Point2 = [-dx * r * 0.45, -dy * r * 0.45];
    const side: Point2 = [-dy * r * 0.6, dx * r * 0.6];
    const d =
      `M ${fmt(tip)} L ${fmt([base[0] + side[0], base[1] + side[1]])} ` +
      `L ${fmt([base[0] - side[0], base[1] - side[1]])} Z`;
    parts.push(svgEl("path", { class: "layout-handle-arrow", d }));
  }
  return svgEl(
    "g",
    {
      class: classes.filter(Boolean).join(" "),
      "data-testid": `layout-handle-${h.index}`,
      "data-corner": h.index,
      "data-pinned": String(h.pinned),
      "data-clamped": String(h.clamped),
      "data-x": h.corner[0].toFixed(2),
      "data-y": h.corner[1].toFixed(2),
      transform: `translate(${h.at[0].toFixed(1)} ${h.at[1].toFixed(1)})`,
    },
    ...parts,
  );
}
