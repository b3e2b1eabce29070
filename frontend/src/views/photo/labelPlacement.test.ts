// Labels on a crowded photo: none overlaps another or a flag, all stay in the drawing, a label
// with room stays on its object, and the same scene always gives the same places.
import { describe, expect, it } from "vitest";
import type { Rect } from "./cornerHandles";
import { type LabelRequest, placeLabels, rectsOverlap } from "./labelPlacement";

// A 640 x 480 photo with a 40 px margin.
const BOUNDS: Rect = { left: -40, top: -40, right: 680, bottom: 520 };
const SIZE = 14;

function label(id: string, box: [number, number, number, number]): LabelRequest {
  const [x1, y1, x2, y2] = box;
  return {
    id,
    anchor: [(x1 + x2) / 2, (y1 + y2) / 2],
    box,
    width: SIZE * 0.62 * id.length + 8,
    height: SIZE * 1.3,
  };
}

/** 24 objects in a cluttered corner: small boxes side by side and stacked, plus big ones. */
function crowdedScene(): LabelRequest[] {
  const requests: LabelRequest[] = [];
  for (let i = 0; i < 20; i++) {
    const x = 120 + (i % 5) * 22;
    const y = 150 + Math.floor(i / 5) * 18;
    requests.push(label(`object_${i}`, [x, y, x + 30, y + 24]));
  }
  requests.push(label("sofa_1", [60, 120, 400, 360]));
  requests.push(label("table_2", [100, 140, 260, 260]));
  requests.push(label("shelf_3", [0, 0, 640, 200]));
  requests.push(label("lamp_4", [140, 160, 160, 180]));
  return requests;
}

const overlapping = (rects: readonly Rect[]) =>
  rects.flatMap((a, i) =>
    rects
      .slice(i + 1)
      .filter((b) => rectsOverlap(a, b))
      .map(() => i),
  );

describe("label placement", () => {
  it("keeps every label apart on a crowded layout", () => {
    const placed = placeLabels(crowdedScene(), BOUNDS);
    expect(placed).toHaveLength(24);
    expect(overlapping(placed.map((p) => p.rect))).toEqual([]);
    // The layout is crowded enough that some labels had to move off their objects.
    expect(placed.some((p) => p.leader)).toBe(true);
    for (const { rect } of placed) {
      expect(rect.left).toBeGreaterThanOrEqual(BOUNDS.left);
      expect(rect.top).toBeGreaterThanOrEqual(BOUNDS.top);
      expect(rect.right).toBeLessThanOrEqual(BOUNDS.right);
      expect(rect.bottom).toBeLessThanOrEqual(BOUNDS.bottom);
    }
  });

  it("keeps labels off the obstacles (flags)", () => {
    const flags: Rect[] = [{ left: 110, top: 140, right: 230, bottom: 230 }];
    const placed = placeLabels(crowdedScene(), BOUNDS, flags);
    for (const { rect } of placed) expect(rectsOverlap(rect, flags[0] as Rect)).toBe(false);
  });

  it("puts a label with room on its object's centroid, without a leader", () => {
    const [lonely] = placeLabels([label("chair", [300, 300, 360, 400])], BOUNDS);
    expect(lonely?.leader).toBe(false);
    const rect = lonely?.rect as Rect;
    expect((rect.left + rect.right) / 2).toBeCloseTo(330);
    expect((rect.top + rect.bottom) / 2).toBeCloseTo(350);
  });

  it("moves the second of two labels on one spot next to it, not far away", () => {
    const [first, second] = placeLabels(
      [label("cup_a", [200, 200, 220, 220]), label("cup_b", [200, 200, 220, 220])],
      BOUNDS,
    );
    expect(rectsOverlap(first?.rect as Rect, second?.rect as Rect)).toBe(false);
    expect(second?.leader).toBe(false);
    expect(Math.abs((second?.rect.top ?? 0) - (first?.rect.top ?? 0))).toBeLessThan(SIZE * 3);
  });

  it("keeps a label at the photo's edge inside the drawing", () => {
    const [edge] = placeLabels([label("picture_on_the_edge", [630, 0, 640, 10])], BOUNDS);
    expect(edge?.rect.right).toBeLessThanOrEqual(BOUNDS.right);
    expect(edge?.rect.top).toBeGreaterThanOrEqual(BOUNDS.top);
  });

  it("is deterministic and independent of the input order", () => {
    const scene = crowdedScene();
    const once = placeLabels(scene, BOUNDS);
    const again = placeLabels([...scene].reverse(), BOUNDS);
    const byId = new Map(again.map((p) => [p.id, p.rect]));
    for (const p of once) expect(byId.get(p.id)).toEqual(p.rect);
  });

  it("finds overlaps when they are there (the check can fail)", () => {
    const a: Rect = { left: 0, top: 0, right: 10, bottom: 10 };
    expect(rectsOverlap(a, { left: 9, top: 9, right: 20, bottom: 20 })).toBe(true);
    expect(rectsOverlap(a, { left: 10.5, top: 0, right: 20, bottom: 10 })).toBe(false);
    expect(rectsOverlap(a, { left: 10.5, top: 0, right: 20, bottom: 10 }, 1)).toBe(true);
  });
});
