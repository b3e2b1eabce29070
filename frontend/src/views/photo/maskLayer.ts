// The mask overlay: one tinted image per object (its box when it has no mask), in the colour
// `colours` gives it (by object or by class, see objectColors.ts). PhotoOverlays keeps each
// object's node and makes a new one only for an object whose mask or colour changed.
import type { Mask, SceneObject } from "@holiscene/schema";
import { svgEl } from "../../dom";
import { type Rgb, rgbCss } from "../classColors";
import { maskImageUrl, type Region } from "./maskRaster";

export const GREY: Rgb = [128, 128, 128];

/**
 * Tinted mask images already encoded, by mask and colour: an object edit redraws the overlay
 * but encodes only the masks that changed (encoding is most of a redraw's time).
 */
const encoded = new Map<string, string>();
const ENCODED_KEPT = 400;

function tintedMask(mask: Mask, colour: Rgb): string {
  const key = `${colour.join(",")}|${mask.origin.join(",")}|${mask.size.join(",")}|${mask.rle.join(",")}`;
  let url = encoded.get(key);
  if (url === undefined) {
    url = maskImageUrl(mask, colour);
    if (encoded.size >= ENCODED_KEPT) encoded.delete(encoded.keys().next().value ?? "");
  } else encoded.delete(key); // most recently used last
  encoded.set(key, url);
  return url;
}

/** An object's node in the mask overlay: its tinted mask image, or its box without a mask. */
export function maskNode(object: SceneObject, region: Region | undefined, colour: Rgb): SVGElement {
  const common = {
    class: "mask",
    "data-testid": `mask-${object.id}`,
    "data-object": object.id,
    "data-colour": rgbCss(colour),
  };
  if (object.mask && region?.bits) {
    const [x, y] = object.mask.origin;
    const [width, height] = object.mask.size;
    return svgEl("image", {
      ...common,
      href: tintedMask(object.mask, colour),
      x,
      y,
      width,
      height,
      preserveAspectRatio: "none",
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
