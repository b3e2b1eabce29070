// Handles of layout corners off the photo: clamped to the drawing's edge, pointing at the
// corner, kept apart; a drag moves the corner as far as the pointer.
import { describe, expect, it } from "vitest";
import {
  clampToRect,
  draggedCorner,
  followPointer,
  insetRect,
  offPhotoText,
  placeHandles,
  type Rect,
} from "./cornerHandles";

// A 640 x 480 photo drawn with a 40 px margin; handles of radius 8.
const AREA: Rect = { left: -40, top: -40, right: 680, bottom: 520 };
const BORDER = insetRect(AREA, 8);

const place = (points: [number, number][], spacing = 20) =>
  placeHandles(
    points.map((point, index) => ({ index, point, pinned: true })),
    AREA,
    BORDER,
    spacing,
  );

describe("corner handles", () => {
  it("puts a handle on a corner in the photo or its margin", () => {
    const [inPhoto, inMargin] = place([
      [100, 200],
      [-30, 500],
    ]);
    expect(inPhoto).toMatchObject({ at: [100, 200], clamped: false, direction: null });
    expect(inMargin).toMatchObject({ at: [-30, 500], clamped: false });
  });

  it("clamps a corner above the photo to the top edge, pointing up", () => {
    const [above] = place([[300, -900]]);
    expect(above?.clamped).toBe(true);
    expect(above?.at).toEqual([300, -32]);
    expect(above?.direction?.[0]).toBeCloseTo(0, 12);
    expect(above?.direction?.[1]).toBeCloseTo(-1, 12);
    expect(above?.corner).toEqual([300, -900]);
  });

  it("clamps a corner beyond a corner of the drawing to that corner, pointing at it", () => {
    const [far] = place([[-340, -432]]);
    expect(far?.at).toEqual([-32, -32]);
    // (-340, -432) - (-32, -32) = (-308, -400), length 504.8...
    const length = Math.hypot(308, 400);
    expect(far?.direction?.[0]).toBeCloseTo(-308 / length, 12);
    expect(far?.direction?.[1]).toBeCloseTo(-400 / length, 12);
  });

  it("is the nearest point of the rectangle", () => {
    expect(clampToRect([1000, 100], BORDER)).toEqual([672, 100]);
    expect(clampToRect([100, 1000], BORDER)).toEqual([100, 512]);
    expect(clampToRect([100, 100], BORDER)).toEqual([100, 100]);
  });

  it("slides a clamped handle along the edge, away from handles already there", () => {
    // Two ceiling corners far above the same spot, and one whose spot a corner in view takes.
    const placed = place(
      [
        [300, -900],
        [305, -2000],
        [-20, 100],
        [-500, 104],
      ],
      20,
    );
    expect(placed.map((h) => h.index)).toEqual([0, 1, 2, 3]);
    expect(placed[0]?.at).toEqual([300, -32]);
    // Beside the first along the top edge, towards the middle (x = 320).
    expect(placed[1]?.at).toEqual([325, -32]);
    expect(placed[1]?.direction?.[1]).toBeLessThan(-0.99);
    // The corner in the margin keeps its place; the clamped one moves down the left edge.
    expect(placed[2]?.at).toEqual([-20, 100]);
    expect(placed[3]?.at[0]).toBe(-32);
    expect(placed[3]?.at[1]).toBeGreaterThanOrEqual(100 + Math.sqrt(20 ** 2 - 12 ** 2) - 1e-9);
  });

  it("at a corner of the drawing slides along the side the corner is mostly beyond", () => {
    const placed = place(
      [
        [-100, -3000],
        [-120, -2000],
      ],
      20,
    );
    expect(placed[0]?.at).toEqual([-32, -32]);
    expect(placed[1]?.at).toEqual([-12, -32]); // along the top edge, to the right
  });

  it("says where a corner off the photo is", () => {
    expect(offPhotoText([300, -420.4], 640, 480)).toBe("off the photo: 420 px up");
    expect(offPhotoText([-30, -420], 640, 480)).toBe("off the photo: 420 px up, 30 px left");
    expect(offPhotoText([700, 500], 640, 480)).toBe("off the photo: 20 px down, 60 px right");
    expect(offPhotoText([10, 10], 640, 480)).toBe("on the photo");
  });

  it("moves a dragged corner as far as the pointer went", () => {
    expect(draggedCorner([300, -900], [300, -32], [340, -12])).toEqual([340, -880]);
  });

  it("lets a clamped handle follow the pointer along the edge while it is dragged", () => {
    // Beyond the top-left corner of the drawing: at rest the handle sits in that corner...
    const [far] = place([[-340, -900]]);
    if (!far) throw new Error("no handle");
    expect(far.at).toEqual([-32, -32]);
    // ...dragged 50 px right and 10 px down, the corner moved as much, and so does the handle
    // (kept inside the drawing), still pointing at the corner.
    const moved = place([[-290, -890]])[0];
    if (!moved) throw new Error("no handle");
    expect(moved.at).toEqual([-32, -32]); // placed afresh it would not move
    const dragged = followPointer(moved, far.at, far.corner, BORDER);
    expect(dragged.at).toEqual([18, -22]);
    const length = Math.hypot(-290 - 18, -890 + 22);
    expect(dragged.direction?.[0]).toBeCloseTo((-290 - 18) / length, 12);
    // Dragged out across the edge, it stays on the edge.
    const out = { ...moved, corner: [-290, -990] as [number, number] };
    expect(followPointer(out, far.at, far.corner, BORDER).at).toEqual([18, -32]);
    // A handle on its corner is left alone.
    const [inside] = place([[100, 100]]);
    if (!inside) throw new Error("no handle");
    expect(followPointer(inside, [0, 0], [50, 50], BORDER)).toBe(inside);
  });
});
