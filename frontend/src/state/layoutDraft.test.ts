// The layout draft: dragged corners re-fit the room; a bad drag keeps the last room and says
// why; the edit sends the corners the fit used, with the distance of an unseen wall.
import type { SceneDocument } from "@holiscene/schema";
import { afterEach, beforeEach, describe, expect, it, vi } from "vitest";
import { boxCorners } from "../geometry/boxes";
import type { Point2, Vec3 } from "../geometry/camera";
import { roomBoxFromCorners, unseenWall, wallDistance } from "../geometry/roomBox";
import { projectRoomCorners } from "../geometry/roomFit";
import { cameraHeight, LayoutDraft } from "./layoutDraft";

const K: [Vec3, Vec3, Vec3] = [
  [500, 0, 320],
  [0, 500, 240],
  [0, 0, 1],
];
const HEIGHT = 1.5;
const PITCH = 12;
const ROLL = -3;

function documentFor(corners: Vec3[]): SceneDocument {
  return {
    scene_id: "s",
    revision: 3,
    updated_at: "2026-01-01T00:00:00Z",
    scene: {
      schema_version: 1,
      name: "room",
      image: { file: "img.png", width: 640, height: 480 },
      camera: {
        K,
        K_source: "given",
        pitch_deg: PITCH,
        roll_deg: ROLL,
        height_m: HEIGHT,
        height_source: "estimated",
        note: null,
      },
      layout: {
        corners_2d: projectRoomCorners(K, PITCH, ROLL, corners),
        corners_3d: corners,
        source: "estimated",
        note: null,
      },
      depth: null,
      objects: [],
      supports: [],
      stages: [],
    },
  } as unknown as SceneDocument;
}

// The camera inside the room looking at the far wall: the near corners are behind it.
const ROOM = boxCorners([1.5, 2.6 / 2 - HEIGHT, 0.2], [5, 2.6, 4], 4);
const inPhoto = ([x, y]: Point2) => x >= -40 && x <= 680 && y >= -40 && y <= 520;

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
  let frames: FrameRequestCallback[] = [];
  const flushFrames = () => {
    const due = frames;
    frames = [];
    for (const callback of due) callback(0);
  };
  beforeEach(() => {
    vi.stubGlobal("requestAnimationFrame", (callback: FrameRequestCallback) => {
      frames.push(callback);
      return frames.length;
    });
    vi.stubGlobal("cancelAnimationFrame", () => {});
  });
  afterEach(() => {
    vi.unstubAllGlobals();
    frames = [];
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
      expect(frames.length).toBe(1);
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

  it("is not available without a stored layout", () => {
    const doc = documentFor(ROOM);
    doc.scene.layout = { corners_2d: null, corners_3d: null, source: null, note: null };
    const draft = new LayoutDraft(doc, inPhoto);
    expect(draft.available).toBe(false);
    draft.setEditing(true);
    expect(draft.editing).toBe(false);
  });
});
