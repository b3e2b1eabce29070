// Support arrows (red: from below, blue: from behind; dashed: not saved yet; dotted with a
// glow: the model's suggestion replacing a guess; faint: the pipeline's guess at under even
// odds, DOUBTFUL_SUPPORT) and anchors of structural supporters (the
// labels and "?" flags are labelLayer.ts's). Each arrow carries its provenance (source,
// author, time, confidence) as data attributes and in its tooltip.
import type { SceneObject } from "@holiscene/schema";
import { formatTime, percentText, svgEl } from "../../dom";
import type { SuggestedSupport } from "../../state/sceneSession";
import { isDoubtfulSupport, isStructural, type ShownSupport } from "../../state/supportGraph";
import {
  arrowFoot,
  arrowShape,
  type Frame,
  type Point,
  type SupporterShape,
  strokeWidth,
  structuralAnchor,
} from "./arrowGeometry";
import { drawingRect, type Rect } from "./cornerHandles";
import { type LabelRequest, placeLabels } from "./labelPlacement";
import type { Region } from "./maskRaster";
import "./supportEditing.css";

/** Objects that hold others up but are never held up themselves. */
export const isRoomPart = (object: SceneObject) => isStructural(object.class);

/** The floor's tag is a short ground bar, not a word: a crowded photo has dozens of objects
 * on the floor, and as many "floor" pills hid the photo (the legend names the bar). */
const isGroundBar = (parent: string) => parent === "floor";

/** Half the width and height of a structural supporter's label. */
function labelHalf(parent: string, size: number): Point {
  if (isGroundBar(parent)) return [size * 0.9, size * 0.22];
  return [(size * (parent.length * 0.62 + 1.2)) / 2, size * 0.75];
}

function anchorLabel(parent: string, at: Point, size: number): SVGGElement {
  const [halfWidth, halfHeight] = labelHalf(parent, size);
  if (isGroundBar(parent))
    return svgEl(
      "g",
      { class: `anchor anchor--${parent}` },
      svgEl("title", {}, parent),
      svgEl("rect", {
        x: at[0] - halfWidth,
        y: at[1] - halfHeight,
        width: 2 * halfWidth,
        height: 2 * halfHeight,
        rx: halfHeight * 0.5,
      }),
    );
  return svgEl(
    "g",
    { class: `anchor anchor--${parent}` },
    svgEl("rect", {
      x: at[0] - halfWidth,
      y: at[1] - halfHeight,
      width: 2 * halfWidth,
      height: 2 * halfHeight,
      rx: halfHeight,
    }),
    svgEl("text", { x: at[0], y: at[1], "font-size": size, dy: "0.35em" }, parent),
  );
}

/** Who set an edge and when, in words (tooltips, the selection bar). */
export function provenanceText(
  support: ShownSupport | null,
  suggestion?: SuggestedSupport,
): string {
  if (suggestion) {
    return `suggested by the model (${percentText(suggestion.probability)}) after your corrections`;
  }
  if (!support) return "no supporter";
  if (support.pending && support.source === "manual") return "your edit, not saved yet";
  const when = support.time ? ` · ${formatTime(support.time)}` : "";
  const unsaved = support.pending ? " (restored, not saved yet)" : "";
  if (support.source === "manual")
    return `manual · ${support.author ?? "unknown"}${when}${unsaved}`;
  const confidence = support.confidence === null ? "" : ` ${percentText(support.confidence)}`;
  return `predicted (auto${confidence})${when}${unsaved}`;
}

interface ArrowEdge {
  parent: string;
  type: string;
  support: ShownSupport | null;
  suggestion?: SuggestedSupport;
}

/**
 * `from`: where a structural supporter's tag is (placed apart from the other tags), or where
 * the arrow leaves an object supporter (`arrowFeet`);
 * `scale`: of the arrow's width and its tag (1 / the photo's zoom keeps their screen size).
 */
function arrowFor(
  edge: ArrowEdge,
  object: SceneObject,
  to: Point | undefined,
  frame: Frame,
  from: Point | undefined,
  scale: number,
): SVGGElement | null {
  if (!to || !from) return null;
  const width = strokeWidth(frame) * scale;
  const labelSize = width * 5;
  const structural = isStructural(edge.parent) ? edge.parent : null;
  const tagGap = structural && isGroundBar(structural) ? labelSize * 0.3 : labelSize * 0.8;
  const gap = structural ? tagGap : width * 1.5;
  const shape = arrowShape(from, to, width, gap);
  // The hit area starts well clear of the arrow's start, on the supporter, where people click
  // to select the supporter itself (short arrows keep most of theirs).
  const length = Math.hypot(to[0] - from[0], to[1] - from[1]);
  const hit = structural
    ? shape
    : arrowShape(from, to, width, Math.max(gap, Math.min(width * 7, length * 0.4)));
  const support = edge.support;
  const suggested = edge.suggestion !== undefined;
  const pending = !suggested && support?.pending === true;
  const classes = ["arrow", `arrow--${edge.type}`];
  if (pending) classes.push("arrow--pending");
  if (suggested) classes.push("arrow--suggested");
  if (!suggested && support?.source === "auto") classes.push("arrow--auto");
  if (!suggested && !pending && isDoubtfulSupport(support)) classes.push("arrow--doubtful");
  const dash = suggested
    ? `${width * 0.8} ${width * 1.6}`
    : pending
      ? `${width * 3} ${width * 2}`
      : undefined;
  const group = svgEl(
    "g",
    {
      class: classes.join(" "),
      "data-testid": `arrow-${object.id}`,
      "data-child": object.id,
      "data-parent": edge.parent,
      "data-type": edge.type,
      "data-pending": String(pending),
      "data-suggested": String(suggested),
      "data-source": suggested ? "model" : (support?.source ?? "none"),
      "data-author": suggested ? undefined : (support?.author ?? undefined),
      "data-time": suggested ? undefined : (support?.time ?? undefined),
      "data-confidence": suggested
        ? edge.suggestion?.probability.toFixed(4)
        : (support?.confidence?.toFixed(4) ?? undefined),
      "data-replaces": suggested && support ? `${support.parent} ${support.type}` : undefined,
    },
    svgEl(
      "title",
      {},
      `${edge.parent} holds up ${object.id} from ${edge.type}: ${provenanceText(support, edge.suggestion)}` +
        (suggested && support ? ` (was ${support.parent}, ${support.type})` : ""),
    ),
    svgEl("path", { class: "arrow-hit", d: hit.shaft, "stroke-width": width * 6 }),
    svgEl("path", { class: "arrow-halo", d: shape.shaft, "stroke-width": width * 2.2 }),
    svgEl("path", {
      class: "arrow-shaft",
      d: shape.shaft,
      "stroke-width": width,
      "stroke-dasharray": dash,
    }),
    svgEl("path", { class: "arrow-head", d: shape.head, "stroke-width": width * 0.6 }),
  );
  if (structural) group.append(anchorLabel(structural, from, labelSize));
  else
    group.prepend(
      svgEl("circle", { class: "arrow-tail", cx: from[0], cy: from[1], r: width * 1.5 }),
    );
  return group;
}

/**
 * Where each arrow from an object supporter starts (arrowFoot). Two children of one supporter
 * one above the other on the photo (a lamp and its shade on a table) would start at the same
 * point and run on one line: each later one is moved aside, alternately right and left, so
 * both arrows show and take clicks.
 */
export function arrowFeet(
  edges: readonly { object: SceneObject; edge: { parent: string; type: string } }[],
  supporters: ReadonlyMap<string, SupporterShape>,
  width: number,
): Map<string, Point> {
  const feet = new Map<string, Point>();
  const placed = new Map<string, Point[]>();
  const apart = width * 4;
  for (const { object, edge } of edges) {
    const to = supporters.get(object.id)?.centroid;
    const supporter = supporters.get(edge.parent);
    if (!to || !supporter || isStructural(edge.parent)) continue;
    const foot = arrowFoot(edge.type, object.bbox, to, supporter, width * 8);
    const others = placed.get(edge.parent) ?? [];
    const clash = (x: number) =>
      others.some((o) => Math.abs(o[0] - x) < apart && Math.abs(o[1] - foot[1]) < apart);
    let x = foot[0];
    for (let step = 1; clash(x) && step <= 8; step++) {
      x = foot[0] + (step % 2 === 1 ? 1 : -1) * Math.ceil(step / 2) * apart;
    }
    const at: Point = [x, foot[1]];
    feet.set(object.id, at);
    placed.set(edge.parent, [...others, at]);
  }
  return feet;
}

interface TagRequest {
  id: string;
  parent: string;
  at: Point;
  half: readonly [number, number];
}

interface SharedTag {
  ids: string[];
  at: Point;
  half: readonly [number, number];
}

/** Tags of one supporter within about a tag's width of each other, joined (greedily, in
 * order) into one tag at their mean place. */
export function sharedTags(tags: readonly TagRequest[]): SharedTag[] {
  const groups: (SharedTag & { parent: string; points: Point[] })[] = [];
  for (const tag of tags) {
    const near = groups.find(
      (g) =>
        g.parent === tag.parent &&
        Math.abs(g.at[0] - tag.at[0]) < 2.5 * tag.half[0] &&
        Math.abs(g.at[1] - tag.at[1]) < 4 * tag.half[1],
    );
    if (!near) {
      groups.push({
        ids: [tag.id],
        parent: tag.parent,
        at: tag.at,
        half: tag.half,
        points: [tag.at],
      });
      continue;
    }
    near.ids.push(tag.id);
    near.points.push(tag.at);
    const n = near.points.length;
    near.at = [
      near.points.reduce((sum, p) => sum + p[0], 0) / n,
      near.points.reduce((sum, p) => sum + p[1], 0) / n,
    ];
  }
  return groups.map(({ ids, at, half }) => ({ ids, at, half }));
}

export function renderArrows(
  group: SVGGElement,
  objects: readonly SceneObject[],
  regions: ReadonlyMap<string, Region>,
  supports: ReadonlyMap<string, ShownSupport>,
  frame: Frame,
  suggestions: ReadonlyMap<string, SuggestedSupport> = new Map(),
  scale = 1,
): Rect[] {
  const supporters = new Map<string, SupporterShape>(
    objects.flatMap((object) => {
      const region = regions.get(object.id);
      if (!region) return [];
      const mask = object.mask && region.bits ? { ...object.mask, bits: region.bits } : null;
      return [[object.id, { bbox: object.bbox, mask, centroid: region.centroid }]];
    }),
  );
  const edges = objects.flatMap((object) => {
    if (isRoomPart(object)) return [];
    const support = supports.get(object.id) ?? null;
    const suggestion = suggestions.get(object.id);
    const edge: ArrowEdge | null = suggestion
      ? { parent: suggestion.parent, type: suggestion.type, support, suggestion }
      : support && { parent: support.parent, type: support.type, support };
    return edge ? [{ object, edge }] : [];
  });
  // The floor, wall and ceiling tags of objects side by side would pile up: the tags of one
  // supporter close together become one tag (a row of books on the wall: one "wall", an arrow
  // to each), and the tags left are placed apart.
  const size = strokeWidth(frame) * scale * 5; // as arrowFor's tags
  const clusters = sharedTags(
    edges.flatMap(({ object, edge }) => {
      const to = supporters.get(object.id)?.centroid;
      if (!to || !isStructural(edge.parent)) return [];
      const half = labelHalf(edge.parent, size);
      const at = structuralAnchor(edge.parent, object, to, frame, half);
      return [{ id: object.id, parent: edge.parent, at, half }];
    }),
  );
  const requests: LabelRequest[] = clusters.map(({ ids, at: [x, y], half: [hw, hh] }) => ({
    id: ids[0] as string,
    anchor: [x, y],
    box: [x - hw, y - hh, x + hw, y + hh] as const,
    width: 2 * hw,
    height: 2 * hh,
  }));
  const anchors = placeLabels(requests, drawingRect(frame), [], size * 0.1);
  const feet = arrowFeet(edges, supporters, strokeWidth(frame) * scale);
  const membersOf = new Map(clusters.map((c) => [c.ids[0] as string, c.ids]));
  const anchorAt = new Map<string, Point>();
  for (const { id, rect } of anchors) {
    const centre: Point = [(rect.left + rect.right) / 2, (rect.top + rect.bottom) / 2];
    for (const member of membersOf.get(id) ?? []) anchorAt.set(member, centre);
  }
  const arrows = edges.flatMap(({ object, edge }) => {
    const to = supporters.get(object.id)?.centroid;
    const from = isStructural(edge.parent) ? anchorAt.get(object.id) : feet.get(object.id);
    const arrow = arrowFor(edge, object, to, frame, from, scale);
    return arrow ? [arrow] : [];
  });
  group.replaceChildren(...arrows);
  // Where the anchors' tags are, for the objects' labels to keep clear of.
  return anchors.map((a) => a.rect);
}
