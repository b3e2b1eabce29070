// The mask overlay: one path per object, the mask's pixels filled (its box when it has no
// mask), in the colour `colours` gives it (by object or by class, see objectColors.ts).
// PhotoOverlays keeps each object's node and makes a new one only for an object whose mask or
// colour changed.
import type { SceneObject } from "@holiscene/schema";
import { svgEl } from "../../dom";
import { type Rgb, rgbCss } from "../rgb";
import { maskPathData, type Region } from "./maskRaster";

export const GREY: Rgb = [128, 128, 128];

/** An object's node in the mask overlay: its mask's pixels, or its box without a mask. */
export function maskNode(object: SceneObject, region: Region | undefined, colour: Rgb): SVGElement {
  const common = {
    class: "mask",
    "data-testid": `mask-${object.id}`,
    "data-object": object.id,
    "data-colour": rgbCss(colour),
  };
  if (object.mask && region?.bits) {
    return svgEl("path", {
      ...common,
      d: maskPathData(object.mask),
      fill: rgbCss(colour),
      "data-source": object.mask.source,
    });
  }
  const [x1, y1, x2, y2] = object.bbox;
  return svgEl("rect", {
    ...common,
    x: x1,
    y: y1,
    width: x2 - x1,
    height: y2 - y1,
    fill: rgbCss(colour),
    "data-source": "none",
  });
}

/** Outlines of the boxes of the hovered and selected objects. */
export function renderOutlines(
  group: SVGGElement,
  objects: readonly SceneObject[],
  hovered: string | null,
  selected: string | null,
  width: number,
  colours: ReadonlyMap<string, Rgb>,
): void {
  const outline = (id: string | null, kind: string) => {
    const object = id ? objects.find((o) => o.id === id) : undefined;
    if (!object) return null;
    const [x1, y1, x2, y2] = object.bbox;
    return svgEl("rect", {
      class: `outline outline--${kind}`,
      x: x1,
      y: y1,
      width: x2 - x1,
      height: y2 - y1,
      stroke: rgbCss(colours.get(object.id) ?? GREY),
      "stroke-width": width,
    });
  };
  group.replaceChildren(
    ...[outline(selected, "selected"), outline(hovered, "hovered")].filter(
      (node): node is SVGRectElement => node !== null,
    ),
  );
}
