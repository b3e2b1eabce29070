// Zooming the photo's view: the point under the pointer stays put, the view stays inside the
// frame, and zoom is kept between "all of it" and MAX_ZOOM.
import { describe, expect, it } from "vitest";
import { clampView, MAX_ZOOM, zoomedView } from "./photoZoom";

const FRAME = { x: -10, y: -10, width: 120, height: 80 };

describe("zoomedView", () => {
  it("keeps the image point under the pointer where it was", () => {
    const at: [number, number] = [30, 20];
    const view = zoomedView(FRAME, FRAME, 2, at);
    expect(view.width).toBe(60);
    expect(view.height).toBe(40);
    // The point's place in the view (as a fraction) is unchanged.
    expect((at[0] - view.x) / view.width).toBeCloseTo((at[0] - FRAME.x) / FRAME.width);
    expect((at[1] - view.y) / view.height).toBeCloseTo((at[1] - FRAME.y) / FRAME.height);
  });

  it("never shows less than the whole frame nor zooms past MAX_ZOOM", () => {
    expect(zoomedView(FRAME, FRAME, 0.3, [0, 0])).toEqual(FRAME);
    expect(zoomedView(FRAME, FRAME, 100, [50, 30]).width).toBeCloseTo(FRAME.width / MAX_ZOOM);
  });

  it("a view moved past the frame's edge is pulled back inside", () => {
    expect(clampView(FRAME, { x: 90, y: -50, width: 60, height: 40 })).toEqual({
      x: 50,
      y: -10,
      width: 60,
      height: 40,
    });
  });
});
