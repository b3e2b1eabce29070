// Where the suggested boxes' tags ("table 26%") go: at a corner of their box, above it or just
// inside, the first spot that covers no tag placed before (the surer suggestions place theirs
// first) and none of the objects' own labels; when every spot is taken, the one that covers
// the fewest, or no tag at all for a request that may go without. Deterministic, so tags do
// not jump between redraws.
import type { Rect } from "../../photo/cornerHandles";
import { rectsOverlap } from "../../photo/labelPlacement";

export interface TagRequest {
  box: readonly [number, number, number, number];
  width: number;
  height: number;
}

/** The spots a tag may take around its box, in order of preference (top-left corner first). */
function spots(request: TagRequest): [number, number][] {
  const [x1, y1, x2, y2] = request.box;
  const { width, height } = request;
  return [
    [x1, y1 - height],
    [x1, y1],
    [x2 - width, y1 - height],
    [x2 - width, y1],
    [x1, y2],
    [x1, y2 - height],
  ];
}

/**
 * One rectangle per request, in the requests' order; `order` says who places first (indices
 * into `requests`), `bounds` holds every tag, `taken` is what no tag should cover. A request
 * `mayGoWithout` gets null where every spot would cover another tag.
 */
export function placeTags(
  requests: readonly TagRequest[],
  order: readonly number[],
  bounds: Rect,
  taken: readonly Rect[],
  mayGoWithout: (index: number) => boolean = () => false,
): (Rect | null)[] {
  const placed: (Rect | null)[] = new Array(requests.length).fill(null);
  const occupied = [...taken];
  for (const index of order) {
    const request = requests[index];
    if (!request) continue;
    let best: Rect | null = null;
    let fewest = Number.POSITIVE_INFINITY;
    for (const [x, y] of spots(request)) {
      const left = Math.min(bounds.right - request.width, Math.max(bounds.left, x));
      const top = Math.min(bounds.bottom - request.height, Math.max(bounds.top, y));
      const rect = { left, top, right: left + request.width, bottom: top + request.height };
      const covered = occupied.filter((other) => rectsOverlap(rect, other)).length;
      if (covered < fewest) {
        best = rect;
        fewest = covered;
        if (covered === 0) break;
      }
    }
    if (best && (fewest === 0 || !mayGoWithout(index))) {
      placed[index] = best;
      occupied.push(best);
    }
  }
  return placed;
}
