// The mask overlay: one tinted image per object (its box when it has no mask).
import type { SceneObject } from "@holiscene/schema";
import { svgEl } from "../../dom";
import { classCss, classRgb } from "../classColors";
import { maskImageUrl, type Region } from "./maskRaster";

export function renderMasks(
  group: SVGGElement,
  objects: readonly SceneObject[],
  regions: ReadonlyMap<string, Region>,
): void {
  const nodes = objects.map((object) => {
    const region = regions.get(object.id);
    const common = {
      class: "mask",
      "data-testid": `mask-${object.id}`,
      "data-object": object.id,
    };
    if (object.mask && region?.bits) {
      const [x, y] = object.mask.origin;
      const [width, height] = object.mask.size;
      return svgEl("image", {
        ...common,
        href: maskImageUrl(object.mask, region.bits, classRgb(object.class)),
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
      fill: classCss(object.class),
      "data-source": "none",
    });
  });
  group.replaceChildren(...nodes);
}

/** Outlines of the boxes of the hovered and selected objects. */
export function renderOutlines(
  group: SVGGElement,
  objects: readonly SceneObject[],
  hovered: string | null,
  selected: string | null,
  width: number,
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
      stroke: classCss(object.class),
      "stroke-width": width,
    });
  };
  group.replaceChildren(
    ...[outline(selected, "selected"), outline(hovered, "hovered")].filter(
      (node): node is SVGRectElement => node !== null,
    ),
  );
}
