// Test fixtures (unit tests only): a room seen by a known camera, its scene document, and
// animation frames that run when a test says so.
import type { SceneDocument } from "@holiscene/schema";
import { vi } from "vitest";
import { boxCorners } from "../geometry/boxes";
import type { Point2, Vec3 } from "../geometry/camera";
import { projectRoomCorners } from "../geometry/roomFit";

export const K: [Vec3, Vec3, Vec3] = [
  [500, 0, 320],
  [0, 500, 240],
  [0, 0, 1],
];
export const HEIGHT = 1.5;
export const PITCH = 12;
export const ROLL = -3;

// The camera inside the room looking at the far wall: the near corners are behind it.
export const ROOM = boxCorners([1.5, 2.6 / 2 - HEIGHT, 0.2], [5, 2.6, 4], 4);
/** The photo (640 x 480) and a 40 px margin around it. */
export const inPhoto = ([x, y]: Point2) => x >= -40 && x <= 680 && y >= -40 && y <= 520;

/** A scene with this room (corners_2d projected by the camera), objects and supports. */
export function documentFor(
  corners: Vec3[],
  extra: Partial<Pick<SceneDocument["scene"], "objects" | "supports">> = {},
  revision = 3,
): SceneDocument {
  return {
    scene_id: "s",
    revision,
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
      ...extra,
    },
  } as unknown as SceneDocument;
}

/** Stub requestAnimationFrame: callbacks wait for `flush()`. Undo with vi.unstubAllGlobals. */
export function manualFrames(): { flush: () => void; pending: () => number } {
  let frames: FrameRequestCallback[] = [];
  vi.stubGlobal("requestAnimationFrame", (callback: FrameRequestCallback) => {
    frames.push(callback);
    return frames.length;
  });
  vi.stubGlobal("cancelAnimationFrame", () => {});
  return {
    flush: () => {
      const due = frames;
      frames = [];
      for (const callback of due) callback(0);
    },
    pending: () => frames.length,
  };
}
