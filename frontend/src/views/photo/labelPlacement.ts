// Where object labels go on the photo so that no two overlap in a crowded scene: each label
// tries a few spots around its object (on the centroid, above, below, beside it, the corners
// of its box) and takes the first one that is free; when none is, it searches rings further
// out and is drawn there with a leader line back to its object. Deterministic: the same
// objects always give the same places, so labels do not jump between redraws.
import type { Point2 } from "../../geometry/camera";
import type { Rect } from "./cornerHandles";

export interface LabelRequest {
  id: string;
  /** The point the label names (the object's centroid). */
  anchor: Point2;
  /** The object's box [x1, y1, x2, y2]. */
  box: readonly [number, number, number, number];
  width: number;
  height: number;
}

export interface PlacedLabel {
  id: string;
  anchor: Point2;
  rect: Rect;
  /** Placed away from its object: draw a line from the label to the anchor. */
  leader: boolean;
}

/** Whether two rectangles overlap, or come closer than `gap`. */
export function rectsOverlap(a: Rect, b: Rect, gap = 0): boolean {
  return (
    a.left < b.right + gap &&
    b.left < a.right + gap &&
    a.top < b.bottom + gap &&
    b.top < a.bottom + gap
  );
}

/** The rectangle of `width` x `height` centred on `(x, y)`, moved inside `bounds`. */
function rectAt(x: number, y: number, width: number, height: number, bounds: Rect): Rect {
  const left = Math.min(bounds.right - width, Math.max(bounds.left, x - width / 2));
  const top = Math.min(bounds.bottom - height, Math.max(bounds.top, y - height / 2));
  return { left, top, right: left + width, bottom: top + height };
}

/** Label centres near the object, best first. */
function nearCentres({ anchor: [x, y], box, width, height }: LabelRequest): Point2[] {
  const [x1, y1, x2, y2] = box;
  const dx = width / 2 + 2;
  const dy = height / 2 + 2;
  return [
    [x, y],
    [x, y - height - 2],
    [x, y + height + 2],
    [x + width / 2 + dx, y],
    [x - width / 2 - dx, y],
    [x1 + dx, y1 + dy],
    [x2 - dx, y1 + dy],
    [x1 + dx, y2 - dy],
    [x2 - dx, y2 - dy],
    [x, y1 - dy],
    [x, y2 + dy],
  ];
}

const RING_DIRECTIONS = 16;

/** Centres on rings around the anchor, nearest ring first, up to `reach`. */
function* ringCentres({ anchor: [x, y], height }: LabelRequest, reach: number) {
  const step = height * 1.1;
  for (let radius = step; radius <= reach; radius += step) {
    for (let k = 0; k < RING_DIRECTIONS; k++) {
      // Start straight up and alternate sides, so the nearest free spot above wins.
      const turn = (Math.ceil(k / 2) * (k % 2 === 0 ? -1 : 1) * 2 * Math.PI) / RING_DIRECTIONS;
      const angle = -Math.PI / 2 + turn;
      yield [x + radius * Math.cos(angle), y + radius * Math.sin(angle)] as Point2;
    }
  }
}

const area = ({ box: [x1, y1, x2, y2] }: LabelRequest) => (x2 - x1) * (y2 - y1);

/**
 * Places every label inside `bounds`, apart from each other and from `obstacles` (by at least
 * `gap`). Small objects choose first: a large one has room for its label in many places.
 * Returns the labels in the order given.
 */
export function placeLabels(
  requests: readonly LabelRequest[],
  bounds: Rect,
  obstacles: readonly Rect[] = [],
  gap = 1,
): PlacedLabel[] {
  const taken: Rect[] = [...obstacles];
  const free = (rect: Rect) => !taken.some((other) => rectsOverlap(rect, other, gap));
  const reach = Math.hypot(bounds.right - bounds.left, bounds.bottom - bounds.top);
  const order = [...requests].sort((a, b) => area(a) - area(b) || (a.id < b.id ? -1 : 1));
  const placed = new Map<string, PlacedLabel>();
  for (const request of order) {
    const { width, height, anchor } = request;
    const at = (p: Point2) => rectAt(p[0], p[1], width, height, bounds);
    let choice: PlacedLabel | null = null;
    for (const centre of nearCentres(request)) {
      const rect = at(centre);
      if (free(rect)) {
        choice = { id: request.id, anchor, rect, leader: false };
        break;
      }
    }
    if (!choice) {
      for (const centre of ringCentres(request, reach)) {
        const rect = at(centre);
        if (free(rect)) {
          choice = { id: request.id, anchor, rect, leader: true };
          break;
        }
      }
    }
    // Nowhere free in the whole drawing: on its object, overlapping (never left out).
    choice ??= { id: request.id, anchor, rect: at(anchor), leader: false };
    taken.push(choice.rect);
    placed.set(request.id, choice);
  }
  return requests.map((r) => placed.get(r.id) as PlacedLabel);
}
