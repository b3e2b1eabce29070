// The layout draft: dragged corners re-fit the room; a bad drag keeps the last room and says
// why; the edit sends the corners the fit used, with the distance of an unseen wall.
import { afterEach, beforeEach, describe, expect, it, vi } from "vitest";
import { boxCorners } from "../geometry/boxes";
import type { Point2 } from "../geometry/camera";
import { roomBoxFromCorners, unseenWall, wallDistance } from "../geometry/roomBox";
import { projectRoomCorners } from "../geometry/roomFit";
import { documentFor, HEIGHT, inPhoto, K, manualFrames, PITCH, ROOM } from "../testing/roomScene";
import { cameraHeight, LayoutDraft, type LayoutState } from "./layoutDraft";

describe("room box helpers", () => {
  it("reads back the box of its corners", () => {
    const room = roomBoxFromCorners(ROOM);
    expect(room.center[0]).toBeCloseTo(1.5, 9);
    expect(room.center[1]).toBeCloseTo(1.3 - HEIGHT, 9);
    expect(room.size).toEqual([expect.closeTo(5, 9), expect.closeTo(2.6, 9), expect.closeTo(4, 9)]);
    expect(room.yawDeg).toBeCloseTo(4, 9);
  });

  it("finds the wall no known corner lies on, and its distance from the camera", () => {
    const corners = [null, [1, 1], [2, 2], null, null, [3, 3], [4, 4], null];
    expect(unseenWall(corners)).toEqual({ axis: 0, side: -1 });
    expect(unseenWall(projectRoomCorners(K, 0, 0, boxCorners([4, 0, 0], [1, 1, 1], 0)))).toBe(null);
    // Back wall at local x = 1.5 cos 4 - 0.2 sin 4 - 2.5 (negative: behind the camera).
    const yaw = (4 * Math.PI) / 180;
    const expected = 2.5 - (1.5 * Math.cos(yaw) - 0.2 * Math.sin(yaw));
    expect(wallDistance(roomBoxFromCorners(ROOM), { axis: 0, side: -1 })).toBeCloseTo(expected, 9);
  });
});

describe("LayoutDraft", () => {
  // Animation frames run when the test says so.
  let frames: ReturnType<typeof manualFrames>;
  const flushFrames = () => frames.flush();
  beforeEach(() => {
    frames = manualFrames();
  });
  afterEach(() => {
    vi.unstubAllGlobals();
  });

  it("starts from the stored room and uses the corners in view", () => {
    const draft = new LayoutDraft(documentFor(ROOM), inPhoto);
    expect(draft.available).toBe(true);
    expect(draft.dirty).toBe(false);
    expect(draft.handles().map((h) => h.index)).toEqual([1, 2, 5, 6]);
    expect(draft.live?.pitchDeg).toBe(PITCH);
    expect(draft.edit()).toBeNull(); // nothing moved
    expect(cameraHeight(documentFor(ROOM))).toBe(HEIGHT);
  });

  it("re-fits the room and camera to moved corners", () => {
    const draft = new LayoutDraft(documentFor(ROOM), inPhoto);
    // The corners of a deeper, turned room seen by a camera with another pitch and roll.
    const moved = boxCorners([1.75, 2.6 / 2 - HEIGHT, 0.2], [5.5, 2.6, 4], 7);
    const image = projectRoomCorners(K, 10, -1, moved);
    const changes: string[] = [];
    draft.subscribe((change) => changes.push(change));
    // Dragged in steps: one fit per animation frame, however many moves came in between.
    for (const step of [0.5, 1]) {
      for (const { index, point } of draft.handles()) {
        const target = image[index] as Point2;
        draft.moveCorner(index, [
          point[0] + step * (target[0] - point[0]),
          point[1] + step * (target[1] - point[1]),
        ]);
      }
      expect(frames.pending()).toBe(1);
      flushFrames();
    }
    expect(changes).toEqual(["fit", "fit"]);
    expect(draft.dirty).toBe(true);
    expect(draft.error).toBeNull();
    expect(draft.live?.pitchDeg).toBeCloseTo(10, 6);
    expect(draft.live?.rollDeg).toBeCloseTo(-1, 6);
    // The wall behind the camera keeps the stored distance; the rest follows the corners.
    const far = draft.live?.corners3d[1] ?? [0, 0, 0];
    for (const [i, v] of (moved[1] ?? []).entries()) expect(far[i]).toBeCloseTo(v, 6);
    const edit = draft.edit();
    expect(edit?.kind).toBe("set_layout");
    expect(edit?.corners_2d.map((c) => c !== null)).toEqual([
      false,
      true,
      true,
      false,
      false,
      true,
      true,
      false,
    ]);
    expect(edit?.unseen_wall_distance).toBeCloseTo(
      wallDistance(roomBoxFromCorners(ROOM), { axis: 0, side: -1 }),
      9,
    );
    expect(draft.fitTimes.length).toBe(2);
  });

  it("keeps the last valid room when the corners give none, and says why", () => {
    const draft = new LayoutDraft(documentFor(ROOM), inPhoto);
    const before = draft.live;
    // A ceiling corner dragged below its floor corner.
    const floor = draft.handles().find((h) => h.index === 1)?.point as Point2;
    draft.moveCorner(5, [floor[0], floor[1] + 200]);
    flushFrames();
    expect(draft.error).toMatch(/each side must be between/);
    expect(draft.live).toBe(before);
    expect(draft.edit()).toBeNull();
    draft.reset();
    expect(draft.error).toBeNull();
    expect(draft.dirty).toBe(false);
  });

  it("scales the room about the camera when the camera's height is set by hand", () => {
    const draft = new LayoutDraft(documentFor(ROOM), inPhoto);
    const steps: string[] = [];
    draft.onStep = (label) => steps.push(label);
    const behind = draft.snapshot().unseenDistance ?? 0;
    draft.setCameraHeight(HEIGHT * 1.2);
    expect(steps).toEqual(["set the camera's height to 1.80 m"]);
    expect(draft.dirty).toBe(true);
    expect(draft.cameraHeight).toBeCloseTo(HEIGHT * 1.2, 12);
    // Same corners in the photo, a camera 20% higher: every corner 20% further away.
    for (const [i, corner] of (draft.live?.corners3d ?? []).entries()) {
      for (const [k, v] of corner.entries()) expect(v).toBeCloseTo((ROOM[i]?.[k] ?? 0) * 1.2, 6);
    }
    const edit = draft.edit();
    expect(edit?.camera_height_m).toBeCloseTo(HEIGHT * 1.2, 12);
    expect(edit?.unseen_wall_distance).toBeCloseTo(behind * 1.2, 9);
    // Undo puts the scene's height back, and the stored room.
    draft.applyState({ ...draft.snapshot(), cameraHeightM: null, unseenDistance: behind });
    expect(draft.dirty).toBe(false);
    expect(draft.cameraHeight).toBe(HEIGHT);
    draft.setCameraHeight(-1); // not a height: ignored
    expect(draft.dirty).toBe(false);
  });

  it("is not available without a stored layout and without intrinsics", () => {
    const doc = documentFor(ROOM);
    doc.scene.layout = { corners_2d: null, corners_3d: null, source: null, note: null };
    doc.scene.camera = null;
    const draft = new LayoutDraft(doc, inPhoto);
    expect(draft.available).toBe(false);
    draft.setEditing(true);
    expect(draft.editing).toBe(false);
  });

  it("puts up a room to start from when the scene has none, saved only once a corner moves", () => {
    const doc = documentFor(ROOM);
    doc.scene.layout = { corners_2d: null, corners_3d: null, source: null, note: null };
    const camera = doc.scene.camera;
    if (!camera) throw new Error("the fixture has a camera");
    Object.assign(camera, { pitch_deg: null, roll_deg: null, height_m: null });
    const draft = new LayoutDraft(doc, inPhoto);
    expect(draft.available).toBe(true);
    expect(draft.hasStoredRoom).toBe(false);
    expect(draft.live).toBeNull(); // nothing shown before editing
    draft.setEditing(true);
    expect(draft.starting).toBe(true);
    expect(draft.live?.pitchDeg).toBe(0); // no pitch known: a level camera
    expect(draft.handles().map((h) => h.index)).toEqual([1, 2, 5, 6]);
    expect(draft.dirty).toBe(false);
    expect(draft.edit()).toBeNull();
    // Stopping without a drag takes the room away again.
    draft.setEditing(false);
    expect(draft.live).toBeNull();
    expect(draft.handles()).toEqual([]);

    draft.setEditing(true);
    const start = draft.beginDrag(1);
    if (!start) throw new Error("the starting room's corner 1 has a handle");
    draft.moveCorner(1, [start[0] - 30, start[1] + 10]);
    draft.endDrag();
    expect(draft.starting).toBe(false);
    expect(draft.dirty).toBe(true);
    const edit = draft.edit();
    expect(edit?.corners_2d.filter((c) => c !== null)).toHaveLength(4);
    expect(edit?.unseen_wall_distance).toBeCloseTo(1, 9); // the front wall, behind the camera
    // A moved starting room is the user's: it stays when editing stops, until discarded.
    draft.setEditing(false);
    expect(draft.live).not.toBeNull();
    draft.showStored();
    expect(draft.live).toBeNull();
    expect(draft.dirty).toBe(false);
  });

  it("gives way to a stored room when a revision brings one", () => {
    const doc = documentFor(ROOM);
    doc.scene.layout = { corners_2d: null, corners_3d: null, source: null, note: null };
    const draft = new LayoutDraft(doc, inPhoto);
    draft.setEditing(true);
    expect(draft.live?.pitchDeg).toBe(PITCH); // the scene's pitch and roll are kept
    draft.setDocument(documentFor(ROOM, {}, 4));
    expect(draft.starting).toBe(false);
    expect(draft.hasStoredRoom).toBe(true);
    expect(draft.live?.corners3d).toEqual(ROOM);
  });
});

// The camera looks at the far wall from just inside the near one: the near floor corners are
// in front of it but far off the photo (below, to the sides), the near ceiling corners behind.
const FAR_ROOM = boxCorners([2.35, 2.6 / 2 - HEIGHT, 0.2], [5, 2.6, 4], 4);

describe("LayoutDraft steps and off-photo corners", () => {
  let frames: ReturnType<typeof manualFrames>;
  beforeEach(() => {
    frames = manualFrames();
  });
  afterEach(() => {
    vi.unstubAllGlobals();
  });

  const record = (draft: LayoutDraft) => {
    const steps: { label: string; before: LayoutState; after: LayoutState }[] = [];
    draft.onStep = (label, before, after) => steps.push({ label, before, after });
    return steps;
  };
  const drag = (draft: LayoutDraft, index: number, by: Point2, moves = 3) => {
    const start = draft.beginDrag(index);
    if (!start) throw new Error(`no handle for corner ${index}`);
    for (let k = 1; k <= moves; k++) {
      draft.moveCorner(index, [start[0] + (by[0] * k) / moves, start[1] + (by[1] * k) / moves]);
      frames.flush();
    }
    draft.endDrag();
    return start;
  };
  const maxDifference = (a: number[][] | undefined, b: number[][] | undefined) =>
    Math.max(...(a ?? []).flatMap((p, i) => p.map((v, j) => Math.abs(v - (b?.[i]?.[j] ?? NaN)))));

  it("makes a drag, pointer down to up, one step; its states put the room back and forth", () => {
    const draft = new LayoutDraft(documentFor(ROOM), inPhoto);
    const steps = record(draft);
    const stored = draft.live;
    const start = draft.beginDrag(1) as Point2;
    draft.moveCorner(1, [start[0] + 10, start[1] + 16]);
    frames.flush();
    draft.moveCorner(1, [start[0] + 20, start[1] + 32]);
    frames.flush();
    expect(steps).toHaveLength(0); // not while the button is down
    draft.endDrag();
    expect(steps.map((s) => s.label)).toEqual(["move the room's floor corner 1"]);
    const moved = draft.live;
    expect(draft.dirty).toBe(true);
    expect(maxDifference(moved?.corners3d, stored?.corners3d)).toBeGreaterThan(0.01);

    const step = steps[0] as (typeof steps)[number];
    draft.applyState(step.before); // undo
    expect(draft.dirty).toBe(false);
    expect(draft.live).toEqual(stored);
    expect(draft.edit()).toBeNull();
    expect(draft.handles().find((h) => h.index === 1)?.point).toEqual(start);

    draft.applyState(step.after); // redo
    expect(draft.dirty).toBe(true);
    expect(maxDifference(draft.live?.corners3d, moved?.corners3d)).toBeLessThan(1e-9);
    expect(draft.edit()?.corners_2d[1]).toEqual([start[0] + 20, start[1] + 32]);
  });

  it("a reset is a step too, and a click on a handle is none", () => {
    const draft = new LayoutDraft(documentFor(ROOM), inPhoto);
    const steps = record(draft);
    draft.beginDrag(2);
    draft.endDrag();
    expect(steps).toHaveLength(0);
    drag(draft, 2, [15, 0]);
    draft.reset();
    expect(steps.map((s) => s.label)).toEqual([
      "move the room's floor corner 2",
      "reset the room layout",
    ]);
    expect(draft.dirty).toBe(false);
    draft.applyState((steps[1] as (typeof steps)[number]).before);
    expect(draft.dirty).toBe(true);
  });

  it("gives corners off the photo a handle where the fitted room puts them; a drag pins one", () => {
    const doc = documentFor(FAR_ROOM);
    const draft = new LayoutDraft(doc, inPhoto);
    const steps = record(draft);
    const handles = draft.handles();
    // Corners 4 and 7 are behind the camera: no handle. 0 and 3 are far off the photo.
    expect(handles.map((h) => [h.index, h.pinned])).toEqual([
      [0, false],
      [1, true],
      [2, true],
      [3, false],
      [5, true],
      [6, true],
    ]);
    const far = handles.find((h) => h.index === 3)?.point as Point2;
    const stored = doc.scene.layout?.corners_2d?.[3] as number[];
    expect(far[0]).toBeCloseTo(stored[0] as number, 6);
    expect(far[1]).toBeCloseTo(stored[1] as number, 6);
    expect(far[0]).toBeGreaterThan(1000); // beyond the photo's right edge

    // A click pins nothing; a drag pins the corner and the fit goes through it.
    draft.beginDrag(3);
    draft.endDrag();
    expect(draft.handles().find((h) => h.index === 3)?.pinned).toBe(false);
    expect(steps).toHaveLength(0);
    drag(draft, 3, [-120, -60]);
    expect(draft.error).toBeNull();
    expect(draft.handles().find((h) => h.index === 3)).toMatchObject({
      pinned: true,
      point: [far[0] - 120, far[1] - 60],
    });
    expect(draft.edit()?.corners_2d[3]).toEqual([far[0] - 120, far[1] - 60]);
    expect(steps.map((s) => s.label)).toEqual(["move the room's floor corner 3"]);
    // Undo un-pins it again.
    draft.applyState((steps[0] as (typeof steps)[number]).before);
    expect(draft.handles().find((h) => h.index === 3)?.pinned).toBe(false);
    expect(draft.dirty).toBe(false);
  });

  it("takes a saved revision as stored when it holds the corners as dragged, not older ones", () => {
    const draft = new LayoutDraft(documentFor(FAR_ROOM), inPhoto);
    const changes: string[] = [];
    draft.subscribe((change) => changes.push(change));
    drag(draft, 3, [-120, -60]);
    const sent = draft.version;
    drag(draft, 1, [5, 5]); // moved while the save was on its way
    draft.setDocument(documentFor(FAR_ROOM, {}, 4), sent);
    expect(draft.dirty).toBe(true);
    expect(changes.at(-1)).toBe("document");
    draft.setDocument(documentFor(FAR_ROOM, {}, 5), draft.version);
    expect(draft.dirty).toBe(false);
    expect(changes.at(-1)).toBe("saved");
    // The corner the user pinned stays pinned (at the stored position).
    expect(draft.handles().find((h) => h.index === 3)?.pinned).toBe(true);
  });
});
