// The room layout while an annotator drags its corners: the corners as dragged, which of them
// the fit uses, and the last valid room fit (pitch, roll, room box), re-fitted at most once
// per animation frame. The photo overlay draws it, the 3D view shows it live, and saving sends
// it as a SetLayout edit (the server fits the same corners again, layout_edit.py).
import type { SceneDocument, SetLayout } from "@holiscene/schema";
import type { Point2, Vec3 } from "../geometry/camera";
import { roomBoxFromCorners, unseenWall, wallDistance } from "../geometry/roomBox";
import {
  cornerCoverageProblem,
  fitRoom,
  type RoomBox,
  type RoomFit,
  RoomFitError,
} from "../geometry/roomFit";

/** The layout stage's camera-height prior (backend layout_edit.py: CAMERA_HEIGHT_PRIOR_M). */
export const CAMERA_HEIGHT_PRIOR_M = 1.4;
/** The sides a room may have, metres (layout_edit.py refuses others the same way). */
export const MIN_ROOM_SIDE_M = 0.5;
export const MAX_ROOM_SIDE_M = 100;

/** The largest root-mean-square fit error, as a share of the photo's diagonal (ditto). */
export const MAX_FIT_ERROR = 0.05;

/** Why a fit is not a plausible room (layout_edit.py's messages), or null. */
export function fitProblem(fit: RoomFit, imageWidth: number, imageHeight: number): string | null {
  const { size } = fit.room;
  if (!size.every((s) => s >= MIN_ROOM_SIDE_M && s <= MAX_ROOM_SIDE_M)) {
    const sides = size.map((s) => s.toFixed(2)).join(" x ");
    return (
      `the corners give a room of ${sides} m: each side must be between ` +
      `${MIN_ROOM_SIDE_M} and ${MAX_ROOM_SIDE_M} m`
    );
  }
  const limit = MAX_FIT_ERROR * Math.hypot(imageWidth, imageHeight);
  if (fit.rmsPx > limit) {
    return (
      `the corners do not fit one room box: they are ${fit.rmsPx.toFixed(0)} px off on ` +
      `average (at most ${limit.toFixed(0)} px)`
    );
  }
  return null;
}

/** The room as shown: the camera's pitch and roll and the room box with its corners. */
export interface LiveRoom {
  pitchDeg: number;
  rollDeg: number;
  room: RoomBox;
  corners3d: Vec3[];
}

export type LayoutChange = "mode" | "fit" | "document";

type Corner = Point2 | null;

/** Metres from the camera to the floor, in the order layout_edit.py's camera_height uses. */
export function cameraHeight(doc: SceneDocument): number {
  const height = doc.scene.camera?.height_m;
  if (height != null && height > 0) return height;
  const corners = doc.scene.layout?.corners_3d;
  if (corners) {
    const floor = -corners.slice(0, 4).reduce((sum, c) => sum + (c[1] ?? 0), 0) / 4;
    if (floor > 0) return floor;
  }
  return CAMERA_HEIGHT_PRIOR_M;
}

/** The stored room, or null when the scene has no camera pitch/roll or layout. */
export function storedRoom(doc: SceneDocument): LiveRoom | null {
  const camera = doc.scene.camera;
  const corners = doc.scene.layout?.corners_3d;
  if (!camera || camera.pitch_deg == null || camera.roll_deg == null || !corners) return null;
  const corners3d = corners.map((c) => [c[0], c[1], c[2]] as Vec3);
  return {
    pitchDeg: camera.pitch_deg,
    rollDeg: camera.roll_deg,
    room: roomBoxFromCorners(corners3d),
    corners3d,
  };
}

export class LayoutDraft {
  /** Whether the corner handles are shown and draggable. */
  editing = false;
  /** The room shown: the last valid fit of the dragged corners, else the stored room. */
  live: LiveRoom | null;
  /** Why the dragged corners give no room (the live room is then the last valid one). */
  error: string | null = null;
  /** Duration of every fit since the draft was last reset, milliseconds. */
  readonly fitTimes: number[] = [];

  private doc: SceneDocument;
  private corners: Corner[] = [];
  /** Which corners the fit uses: those in view on the photo when editing began. */
  private used: boolean[] = [];
  private unseenDistance: number | null = null;
  private moved = false;
  private frame = 0;
  private readonly listeners = new Set<(change: LayoutChange) => void>();

  /** `inView(point)`: whether a stored corner is on (or just beside) the photo. */
  constructor(
    doc: SceneDocument,
    private readonly inView: (point: Point2) => boolean,
  ) {
    this.doc = doc;
    this.live = storedRoom(doc);
    this.resetCorners();
  }

  /** Whether there is a stored layout to edit (its corners in the image and the room). */
  get available(): boolean {
    return storedRoom(this.doc) !== null && this.corners.some((c) => c !== null);
  }

  /** Whether the corners were moved since the stored layout (unsaved). */
  get dirty(): boolean {
    return this.moved;
  }

  /** The dragged corners (8, null where unknown) and whether each is used by the fit. */
  handles(): { index: number; point: Point2 }[] {
    return this.corners.flatMap((point, index) =>
      point && this.used[index] ? [{ index, point }] : [],
    );
  }

  subscribe(listener: (change: LayoutChange) => void): () => void {
    this.listeners.add(listener);
    return () => this.listeners.delete(listener);
  }

  setEditing(on: boolean): void {
    if (this.editing === on || (on && !this.available)) return;
    this.editing = on;
    if (on) this.warmUp();
    this.emit("mode");
  }

  /**
   * Fit the stored corners once, result unused: the first call of the fit compiles it (about
   * 30 ms here), which the first step of a drag should not have to wait for.
   */
  private warmUp(): void {
    const camera = this.doc.scene.camera;
    if (!camera) return;
    try {
      fitRoom(camera.K, this.fitCorners(), cameraHeight(this.doc), {
        unseenWallDistance: this.unseenDistance,
      });
    } catch {
      // A stored layout the fit cannot take shows its reason on the first drag.
    }
  }

  /**
   * A new revision was loaded (a support edit saved, a placement job done, someone else's
   * save): show its room, or keep the moved corners, re-fitted, when there are some.
   */
  setDocument(doc: SceneDocument): void {
    this.doc = doc;
    if (this.moved) this.refit();
    else this.reset();
    this.emit("document");
  }

  /** Back to the stored layout. */
  reset(): void {
    this.cancelFrame();
    this.live = storedRoom(this.doc);
    this.error = null;
    this.moved = false;
    this.fitTimes.length = 0;
    this.resetCorners();
    this.emit("fit");
  }

  /** Move a corner; the room is re-fitted on the next animation frame. */
  moveCorner(index: number, point: Point2): void {
    if (!this.used[index]) return;
    this.corners[index] = point;
    this.moved = true;
    this.frame ||= requestAnimationFrame(() => {
      this.frame = 0;
      this.refit();
    });
  }

  /** Fit the room to the corners now (also what a pending animation frame does). */
  refit(): void {
    this.cancelFrame();
    const camera = this.doc.scene.camera;
    if (!camera) return;
    const start = performance.now();
    try {
      const fit = fitRoom(camera.K, this.fitCorners(), cameraHeight(this.doc), {
        unseenWallDistance: this.unseenDistance,
      });
      const { width, height } = this.doc.scene.image;
      const problem = fitProblem(fit, width, height);
      if (problem !== null) throw new RoomFitError(problem);
      this.live = {
        pitchDeg: fit.pitchDeg,
        rollDeg: fit.rollDeg,
        room: fit.room,
        corners3d: fit.corners3d,
      };
      this.error = null;
    } catch (error) {
      if (!(error instanceof RoomFitError)) throw error;
      this.error = error.message;
    }
    this.fitTimes.push(performance.now() - start);
    this.emit("fit");
  }

  /** The edit that stores the dragged corners; null while they give no room. */
  edit(): SetLayout | null {
    if (this.error !== null || !this.moved) return null;
    const corners = this.fitCorners().map((c) => (c ? ([c[0], c[1]] as [number, number]) : null));
    return {
      kind: "set_layout",
      corners_2d: corners as SetLayout["corners_2d"],
      unseen_wall_distance: this.unseenDistance,
    };
  }

  private cancelFrame(): void {
    if (this.frame !== 0) cancelAnimationFrame(this.frame);
    this.frame = 0;
  }

  private fitCorners(): Corner[] {
    return this.corners.map((c, i) => (this.used[i] ? c : null));
  }

  /**
   * The stored corners; the fit uses those in view (the others were extrapolated by the last
   * fit, and anchoring to them would resist every drag), or all known ones when the corners
   * in view cannot determine the room. A wall with no corner in view keeps its distance.
   */
  private resetCorners(): void {
    const stored = this.doc.scene.layout?.corners_2d ?? [];
    this.corners = Array.from({ length: 8 }, (_, i) => {
      const c = stored[i];
      return c ? ([c[0], c[1]] as Point2) : null;
    });
    const room = this.live?.room ?? null;
    const choose = (inView: boolean[]) => {
      const corners = this.corners.map((c, i) => (inView[i] ? c : null));
      const wall = unseenWall(corners);
      const distance = wall && room ? wallDistance(room, wall) : null;
      const usable =
        (distance === null || distance > 0) && cornerCoverageProblem(corners, distance) === null;
      return { inView, distance, usable };
    };
    const visible = choose(this.corners.map((c) => c !== null && this.inView(c)));
    const fallback = choose(this.corners.map((c) => c !== null));
    const chosen = visible.usable ? visible : fallback;
    this.used = chosen.inView;
    this.unseenDistance = chosen.distance;
  }

  private emit(change: LayoutChange): void {
    for (const listener of this.listeners) listener(change);
  }
}
