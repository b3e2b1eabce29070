// The detector's suggested boxes over the photo: dashed boxes with class and score, larger
// ones first so a smaller box inside one stays clickable, and every tag over every box, so a
// box's tag is never under another box; a click on a box or its tag selects it. The tags keep
// clear of each other and of the objects' labels (offerLabelPlacement.ts); a guess whose
// tag finds no free spot goes without one until it is selected (its class in its tooltip and
// in the bar): on a dense shelf fifteen "books" tags piled up, cut to "b".
import { percentText, svgEl } from "../../../dom";
import { type Frame, strokeWidth } from "../../photo/arrowGeometry";
import type { Rect } from "../../photo/cornerHandles";
import { drawnLabelTags } from "../../photo/labelLayer";
import { type Offer, offerLabel } from "../detectionOffers";
import { placeTags } from "./offerLabelPlacement";

/** The tag's font size and box for a label of this text. */
function tagSize(label: string, frame: Frame): { size: number; width: number; height: number } {
  const size = strokeWidth(frame) * 5;
  return { size, width: label.length * size * 0.62 + size * 0.6, height: size * 1.35 };
}

/** The offer's box and, drawn over all boxes, its tag (if it has a place): both select it
 * (`data-key`). */
function offerBox(
  offer: Offer,
  selected: boolean,
  frame: Frame,
  tagRect: Rect | null,
): { box: SVGGElement; tag: SVGGElement | null } {
  const stroke = strokeWidth(frame);
  const [x1, y1, x2, y2] = offer.bbox;
  const label = offerLabel(offer);
  const { size } = tagSize(label, frame);
  const classes = `detector-suggestion${selected ? " is-selected" : ""}${offer.faint ? " is-faint" : ""}`;
  const title = `Suggested ${label} (the detector's ${offer.sourceClass}): click to select`;
  const box = svgEl(
    "g",
    {
      class: classes,
      "data-testid": "detector-suggestion",
      "data-key": offer.key,
      "data-class": offer.cls,
      "data-score": percentText(offer.score).slice(0, -1),
      "data-bbox": offer.bbox.map((v) => v.toFixed(1)).join(","),
    },
    svgEl("title", {}, title),
    svgEl("rect", {
      class: "detector-box-halo",
      x: x1,
      y: y1,
      width: x2 - x1,
      height: y2 - y1,
      "stroke-width": stroke * (selected ? 2.2 : 1.6),
    }),
    svgEl("rect", {
      class: "detector-box",
      x: x1,
      y: y1,
      width: x2 - x1,
      height: y2 - y1,
      "stroke-width": stroke * (selected ? 1.4 : 0.9),
      "stroke-dasharray": `${stroke * 4} ${stroke * 2.5}`,
    }),
  );
  if (!tagRect) return { box, tag: null };
  const { left, top } = tagRect;
  const labelWidth = tagRect.right - tagRect.left;
  const labelHeight = tagRect.bottom - tagRect.top;
  const tag = svgEl(
    "g",
    {
      class: `${classes} detector-suggestion-tag`,
      "data-testid": "detector-suggestion-tag",
      "data-key": offer.key,
    },
    svgEl("title", {}, title),
    svgEl("rect", {
      class: "detector-label-box",
      x: left,
      y: top,
      width: labelWidth,
      height: labelHeight,
      rx: size * 0.25,
    }),
    svgEl(
      "text",
      {
        class: "detector-label",
        x: left + size * 0.3,
        y: top + labelHeight / 2,
        dy: "0.35em",
        "font-size": size,
      },
      label,
    ),
  );
  return { box, tag };
}

const area = (offer: Offer) => (offer.bbox[2] - offer.bbox[0]) * (offer.bbox[3] - offer.bbox[1]);

export interface OfferBoxes {
  layer: SVGGElement;
  /** Draw the open offers, `selected` (a key) highlighted. */
  draw(open: readonly Offer[], selected: string | null): void;
}

/**
 * The boxes' layer, added to the photo's SVG; `onSelect` hears the key of a clicked box. A
 * click on a box is not a click on the photo (arrow editing).
 */
export function offerBoxes(
  svg: SVGSVGElement,
  frame: Frame,
  photoWidth: number,
  onSelect: (key: string | null) => void,
): OfferBoxes {
  const layer = svgEl("g", { class: "detector-layer", "data-testid": "detector-layer" });
  svg.append(layer);
  const pick = (event: Event) => {
    const group = (event.target as Element).closest<SVGGElement>(".detector-suggestion");
    if (!group) return;
    event.stopPropagation();
    if (event.type === "click") onSelect(group.dataset.key ?? null);
  };
  layer.addEventListener("click", pick);
  layer.addEventListener("pointerdown", pick);
  return {
    layer,
    draw(open, selected) {
      const byArea = [...open].sort((a, b) => area(b) - area(a));
      const requests = byArea.map((offer) => ({
        box: offer.bbox,
        ...tagSize(offerLabel(offer), frame),
      }));
      // The selected box places its tag first, then the suggestions, then the guesses, each
      // the surer ones first (a guess's score is its own detector's).
      const rank = byArea.map((offer) =>
        offer.key === selected ? 3 : offer.score + (offer.faint ? 0 : 1),
      );
      const surest = rank.map((_, i) => i).sort((a, b) => (rank[b] ?? 0) - (rank[a] ?? 0));
      const bounds = {
        left: -frame.margin,
        top: -frame.margin,
        right: photoWidth + frame.margin,
        bottom: frame.height + frame.margin,
      };
      const tags = placeTags(
        requests,
        surest,
        bounds,
        drawnLabelTags(svg).map((tag) => tag.rect),
        (i) => {
          const offer = byArea[i] as Offer;
          return offer.faint && offer.key !== selected;
        },
      );
      const drawn = byArea.map((offer, i) =>
        offerBox(offer, offer.key === selected, frame, tags[i] ?? null),
      );
      // Tags the placement could not keep apart overlap: the likelier one on top.
      const tagsFaintFirst = [...surest].reverse().flatMap((i) => drawn[i]?.tag ?? []);
      layer.replaceChildren(...drawn.map((d) => d.box), ...tagsFaintFirst);
    },
  };
}
