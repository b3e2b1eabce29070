// Object labels on the photo (each object's id on a dark tag with its mask colour), placed
// apart by labelPlacement.ts, with a leader line when a crowd pushed the tag off its object;
// and a "?" flag on objects without a supporter (at its centroid, where its arrow would end).
// Labels keep clear of the flags and of the centroids, where the support arrows end.
import type { SceneObject } from "@holiscene/schema";
import { svgEl } from "../../dom";
import { objectClassText } from "../../state/classNames";
import { type ShownSupport, withoutSupporter } from "../../state/supportGraph";
import { type Rgb, rgbCss } from "../rgb";
import { type Frame, strokeWidth } from "./arrowGeometry";
import { clampToRect, drawingRect, type Rect } from "./cornerHandles";
import { type LabelRequest, placeLabels } from "./labelPlacement";
import type { Region } from "./maskRaster";

/** Width of one character of the labels' monospace font, in em (with a little to spare). */
const CHAR_EM = 0.62;

/** The tag's parts in multiples of the font size. */
const PAD = 0.4;
const SWATCH = 0.45;
const HEIGHT = 1.4;

/** The "?" flag sits where the object's arrow would end (its centroid): inside its own mask,
 * never on a corner another object's box may cover. */
function flagFor(
  object: SceneObject,
  size: number,
  centroid: readonly [number, number],
): { node: SVGGElement; rect: Rect } {
  const [cx, cy, r] = [centroid[0], centroid[1], size * 0.9];
  const node = svgEl(
    "g",
    {
      class: "unsupported-flag",
      "data-testid": `unsupported-${object.id}`,
      "data-unsupported": object.id,
    },
    svgEl("title", {}, `${object.id} has no supporter: click, then click what holds it up`),
    svgEl("circle", { cx, cy, r }),
    svgEl("text", { x: cx, y: cy, dy: "0.35em", "font-size": size * 1.2 }, "?"),
  );
  return { node, rect: { left: cx - r, top: cy - r, right: cx + r, bottom: cy + r } };
}

function tag(
  object: SceneObject,
  rect: Rect,
  anchor: [number, number] | null,
  size: number,
  colour: Rgb,
): SVGGElement {
  const height = rect.bottom - rect.top;
  const textWidth = object.id.length * CHAR_EM * size;
  const group = svgEl(
    "g",
    {
      class: "object-label",
      "data-testid": `label-${object.id}`,
      "data-object": object.id,
      "data-leader": String(anchor !== null),
    },
    // The tag is short (the id) so a crowded photo stays readable; hovering names the class.
    svgEl("title", {}, `${object.id}: ${objectClassText(object)}`),
  );
  if (anchor) {
    const [ex, ey] = clampToRect(anchor, rect);
    group.append(
      svgEl("line", {
        class: "label-leader",
        x1: anchor[0],
        y1: anchor[1],
        x2: ex,
        y2: ey,
        "stroke-width": size * 0.14,
      }),
      svgEl("circle", { class: "label-anchor", cx: anchor[0], cy: anchor[1], r: size * 0.22 }),
    );
  }
  group.append(
    svgEl("rect", {
      class: "label-box",
      x: rect.left,
      y: rect.top,
      width: rect.right - rect.left,
      height,
      rx: size * 0.25,
    }),
    svgEl("rect", {
      class: "label-swatch",
      x: rect.left + size * 0.2,
      y: rect.top + size * 0.3,
      width: SWATCH * size,
      height: height - size * 0.6,
      fill: rgbCss(colour),
    }),
    // textLength: the tag fits its text whatever monospace font the browser picked.
    svgEl(
      "text",
      {
        class: "label-text",
        x: rect.left + (0.2 + SWATCH + PAD * 0.6) * size,
        y: rect.top + height / 2,
        dy: "0.35em",
        "font-size": size,
        textLength: textWidth,
        lengthAdjust: "spacingAndGlyphs",
      },
      object.id,
    ),
  );
  return group;
}

/**
 * Labels and flags for every object; `colours` as the masks are coloured; `keepClear`: more
 * places labels must not cover (the support arrows' anchor tags); `scale`: of the labels'
 * size (1 / the photo's zoom keeps them the same size on the screen).
 */
export function renderLabels(
  group: SVGGElement,
  objects: readonly SceneObject[],
  regions: ReadonlyMap<string, Region>,
  supports: ReadonlyMap<string, ShownSupport>,
  frame: Frame,
  colours: ReadonlyMap<string, Rgb>,
  keepClear: readonly Rect[] = [],
  scale = 1,
): void {
  const size = strokeWidth(frame) * 5.5 * scale;
  const flags = withoutSupporter(objects, supports)
    .filter((o) => regions.has(o.id))
    .map((o) => flagFor(o, size, (regions.get(o.id) as Region).centroid));
  const requests: LabelRequest[] = objects.flatMap((object) => {
    const region = regions.get(object.id);
    if (!region) return [];
    const width = (object.id.length * CHAR_EM + 0.2 + SWATCH + PAD * 1.6) * size;
    return [
      { id: object.id, anchor: region.centroid, box: object.bbox, width, height: HEIGHT * size },
    ];
  });
  // Arrowheads end on the centroids: labels keep them in view.
  const heads = requests.map(({ anchor: [x, y] }) => {
    const r = size * 0.45;
    return { left: x - r, top: y - r, right: x + r, bottom: y + r };
  });
  const placed = placeLabels(
    requests,
    drawingRect(frame),
    [...flags.map((f) => f.rect), ...heads, ...keepClear],
    size * 0.1,
  );
  const byId = new Map(objects.map((o) => [o.id, o]));
  const tags = placed.flatMap((p) => {
    const object = byId.get(p.id);
    if (!object) return [];
    const colour = colours.get(p.id) ?? [128, 128, 128];
    return [tag(object, p.rect, p.leader ? p.anchor : null, size, colour)];
  });
  group.replaceChildren(...tags, ...flags.map((f) => f.node));
}

/** The label tags drawn under `root` (the photo's SVG or its labels layer), each with its
 * object and rectangle in photo pixels, in drawing order (the topmost last). */
export function drawnLabelTags(root: Element): { id: string; rect: Rect }[] {
  return [...root.querySelectorAll<SVGRectElement>(".object-label .label-box")].map((box) => {
    const left = box.x.baseVal.value;
    const top = box.y.baseVal.value;
    return {
      id: box.closest<SVGGElement>(".object-label")?.dataset.object ?? "",
      rect: {
        left,
        top,
        right: left + box.width.baseVal.value,
        bottom: top + box.height.baseVal.value,
      },
    };
  });
}
