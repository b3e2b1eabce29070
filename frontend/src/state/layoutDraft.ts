// The room layout while an annotator drags its corners: the corners as dragged, which of them
// the fit uses, and the last valid room fit (pitch, roll, room box), re-fitted at most once
// per animation frame. The photo overlay draws it, the 3D view shows it live, and saving sends
// it as a SetLayout edit (the server fits the same corners again, editing/layout.py).
import type { SceneDocument, SetLayout } from "@holiscene/schema";
import type { Point2, Vec3 } from "../geometry/camera";
import { roomBoxFromCorners, unseenWall, wallDistance } from "../geometry/roomBox";
import {
  cornerCoverageProblem,
  fitRoom,
  projectRoomCorners,
  type RoomBox,
  type RoomFit,
  RoomFitError,
} from "../geometry/roomFit";
import { type StarterRoom, starterRoom } from "../geometry/starterRoom";

/** The layout stage's camera-height prior (backend editing/layout.py: CAMERA_HEIGHT_PRIOR_M). */
export const CAMERA_HEIGHT_PRIOR_M = 1.4;
/** The camera heights an annotator may set, metres (SetLayout.camera_height_m's range). */
export const CAMERA_HEIGHT_RANGE_M: readonly [number, number] = [0.1, 20];
/** The sides a room may have, metres (editing/layout.py refuses others the same way). */
export const MIN_ROOM_SIDE_M = 0.5;
export const MAX_ROOM_SIDE_M = 100;

/** The largest root-mean-square fit error, as a share of the photo's diagonal (ditto). */
export const MAX_FIT_ERROR = 0.05;

/** Why a fit is not a plausible room (editing/layout.py's messages), or null. */
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

/** What changed: editing on or off, the fitted room, the revision (`saved`: one that stored
 * the corners as dragged). */
export type LayoutChange = "mode" | "fit" | "document" | "saved";

type Corner = Point2 | null;

/**
 * What undo and redo put back of the layout (and what a draft in localStorage keeps): the
 * corners as dragged, which of them the fit uses, the distance of a wall none of them places,
 * and the camera's height when the annotator set it (null: the scene's). Plain JSON.
 */
export interface LayoutState {
  corners: Corner[];
  used: boolean[];
  unseenDistance: number | null;
  /** Metres; drafts kept before it existed lack it (read as null). */
  cameraHeightM: number | null;
}

/** How far the fitted room may pass from a corner put by hand before the page says so, as a
 * share of the photo's diagonal: a box room cannot reach every point a corner is dropped on. */
export const MISS_SHARE = 0.025;

/** A corner put by hand that the fitted room passes far from: it goes to `fitted` when saved. */
export interface CornerMiss {
  index: number;
  name: string;
  corner: Point2;
  fitted: Point2;
  px: number;
}

/** A corner handle: where the corner is, and whether the fit uses it (pinned) or places it. */
export interface CornerHandle {
  index: number;
  point: Point2;
  /** Dragged or in view: the fit goes through it. Otherwise it follows the fitted room. */
  pinned: boolean;
}

/** One undoable step of the layout: a corner drag, a reset. */
export type LayoutStep = (label: string, before: LayoutState, after: LayoutState) => void;

/** Image pixels below which two corner positions are the same. */
const SAME_PX = 1e-3;

const copyState = (state: LayoutState): LayoutState => ({
  corners: state.corners.map((c) => (c ? ([c[0], c[1]] as Point2) : null)),
  used: [...state.used],
  unseenDistance: state.unseenDistance,
  cameraHeightM: state.cameraHeightM ?? null,
});

const samePoint = (a: Corner | undefined, b: Corner | undefined) =>
  a == null || b == null
    ? a == null && b == null
    : Math.abs(a[0] - b[0]) <= SAME_PX && Math.abs(a[1] - b[1]) <= SAME_PX;

/** Whether two layout states give the fit the same corners (unseen-wall distance, camera
 * height). */
export function sameLayout(a: LayoutState, b: LayoutState): boolean {
  return (
    a.unseenDistance === b.unseenDistance &&
    (a.cameraHeightM ?? null) === (b.cameraHeightM ?? null) &&
    a.used.every((u, i) => u === b.used[i]) &&
    a.corners.every((c, i) => !a.used[i] || samePoint(c, b.corners[i]))
  );
}

const cornerName = (index: number) => `${index < 4 ? "floor" : "ceiling"} corner ${index}`;

/** Metres from the camera to the floor stored with the scene, in the order editing/layout.py's
 * camera_height uses. */
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
/** What the stored room is made from: the layout's corners and the camera's pitch and roll. */
function storedLayoutKey(doc: SceneDocument): string {
  const { layout, camera } = doc.scene;
  return JSON.stringify([
    layout?.corners_2d,
    layout?.corners_3d,
    camera?.pitch_deg,
    camera?.roll_deg,
  ]);
}

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
  /** Counts every change of the corners: a save knows whether it stored the latest ones. */
  version = 0;
  /** Told of every finished step (a drag, a reset), for undo and redo. */
  onStep: LayoutStep | null = null;

  private doc: SceneDocument;
  private corners: Corner[] = [];
  /** Which corners the fit uses: those in view on the photo when editing began. */
  private used: boolean[] = [];
  private unseenDistance: number | null = null;
  /** The camera's height set by hand in this draft (metres), or null for the scene's. */
  private cameraHeightM: number | null = null;
  private moved = false;
  /** The room editing started from when the scene has none stored (see starterRoom). */
  private starter: StarterRoom | null = null;
  private frame = 0;
  /** The state when the corner being dragged was grabbed. */
  private dragStart: { index: number; from: Point2; state: LayoutState } | null = null;
  private readonly listeners = new Set<(change: LayoutChange) => void>();

  /** `inView(point)`: whether a stored corner is on (or just beside) the photo. */
  constructor(
    doc: SceneDocument,
    private readonly inView: (point: Point2) => boolean,
  ) {
    this.doc = doc;
    this.live = storedRoom(doc);
    this.setState(this.storedState());
  }

  /** Whether there is a layout to edit: a stored one (its corners in the image and the
   * room), or, for a scene with intrinsics and no room, a starting room editing puts up. */
  get available(): boolean {
    if (storedRoom(this.doc) === null) return this.doc.scene.camera != null;
    return this.corners.some((c) => c !== null);
  }

  /** Whether the scene has a stored room (what a placement job places the objects in). */
  get hasStoredRoom(): boolean {
    return storedRoom(this.doc) !== null;
  }

  /** Whether the room shown is the starting room of a scene with none stored, unmoved. */
  get starting(): boolean {
    return this.starter !== null && !this.moved;
  }

  /** The camera's height the room is fitted with: set by hand in this draft, else the scene's. */
  get cameraHeight(): number {
    return this.cameraHeightM ?? cameraHeight(this.doc);
  }

  /**
   * Set the camera's height by hand (metres; the scale of the whole room, which no photo
   * tells): one undoable step. A wall no corner places keeps its place relative to the room,
   * so the room scales about the camera. False (and nothing changes) for a height outside
   * CAMERA_HEIGHT_RANGE_M.
   */
  setCameraHeight(metres: number): boolean {
    const [low, high] = CAMERA_HEIGHT_RANGE_M;
    if (!(metres >= low && metres <= high)) return false;
    if (Math.abs(metres - this.cameraHeight) < 1e-9) return true;
    const before = this.snapshot();
    const ratio = metres / this.cameraHeight;
    if (this.unseenDistance !== null) this.unseenDistance *= ratio;
    this.cameraHeightM = metres;
    this.version++;
    this.settle();
    this.record(`set the camera's height to ${metres.toFixed(2)} m`, before);
    return true;
  }

  /** Whether the corners were moved since the stored layout (unsaved). */
  get dirty(): boolean {
    return this.moved;
  }

  /** Whether a corner is being dragged. */
  get dragging(): boolean {
    return this.dragStart !== null;
  }

  /**
   * A handle for every corner in front of the camera: the corners the fit uses where they
   * were put, the others where the fitted room puts them (dragging one pins it).
   */
  handles(): CornerHandle[] {
    const K = this.doc.scene.camera?.K;
    const live = this.live;
    const placed =
      K && live ? projectRoomCorners(K, live.pitchDeg, live.rollDeg, live.corners3d) : [];
    return this.corners.flatMap((corner, index) => {
      const pinned = this.used[index] === true;
      const point = pinned ? corner : (placed[index] ?? null);
      return point ? [{ index, point, pinned }] : [];
    });
  }

  /** The corner put by hand that the fitted room misses most, beyond MISS_SHARE, or null. */
  miss(): CornerMiss | null {
    const K = this.doc.scene.camera?.K;
    const live = this.live;
    if (!K || !live || this.error !== null) return null;
    const fitted = projectRoomCorners(K, live.pitchDeg, live.rollDeg, live.corners3d);
    const { width, height } = this.doc.scene.image;
    let worst: CornerMiss | null = null;
    let limit = MISS_SHARE * Math.hypot(width, height);
    for (const [index, corner] of this.corners.entries()) {
      const at = fitted[index];
      if (!this.used[index] || !corner || !at) continue;
      const px = Math.hypot(corner[0] - at[0], corner[1] - at[1]);
      if (px <= limit) continue;
      limit = px;
      worst = { index, name: cornerName(index), corner, fitted: at, px };
    }
    return worst;
  }

  subscribe(listener: (change: LayoutChange) => void): () => void {
    this.listeners.add(listener);
    return () => this.listeners.delete(listener);
  }

  setEditing(on: boolean): void {
    if (this.editing === on || (on && !this.available)) return;
    this.editing = on;
    if (on && storedRoom(this.doc) === null) this.putUpStarter();
    // An untouched starting room goes when editing stops: nothing of it was the user's.
    if (!on && this.starter !== null && !this.moved) this.toStored();
    if (on) this.warmUp();
    this.emit("mode");
  }

  private putUpStarter(): void {
    const camera = this.doc.scene.camera;
    if (!camera) return;
    const { width, height } = this.doc.scene.image;
    this.starter = starterRoom(
      camera.K,
      width,
      height,
      this.cameraHeight,
      camera.pitch_deg ?? 0,
      camera.roll_deg ?? 0,
    );
    this.toStored();
  }

  /**
   * Fit the stored corners once, result unused: the first call of the fit compiles it (about
   * 30 ms here), which the first step of a drag should not have to wait for.
   */
  private warmUp(): void {
    const camera = this.doc.scene.camera;
    if (!camera) return;
    try {
      fitRoom(camera.K, this.fitCorners(), this.cameraHeight, {
        unseenWallDistance: this.unseenDistance,
      });
    } catch {
      // A stored layout the fit cannot take shows its reason on the first drag.
    }
  }

  /**
   * A new revision was loaded (a save, a placement job, someone else's save): show its room,
   * or keep the moved corners, re-fitted, when there are some. `savedVersion`: the version of
   * the corners this revision stored (they are then the stored layout, not unsaved changes).
   */
  setDocument(doc: SceneDocument, savedVersion: number | null = null): void {
    const before = this.doc;
    this.doc = doc;
    if (storedRoom(doc) !== null) this.starter = null;
    if (savedVersion !== null && savedVersion === this.version && !this.dragging) {
      // The user's pinned corners stay pinned, at the stored (fitted) positions.
      this.toStored(this.used);
      this.emit("saved");
      return;
    }
    if (this.moved) this.refit();
    // A revision with the same stored room (an object edit, most of them) leaves the room
    // shown as it is: no fit, nothing for the room's listeners to redraw.
    else if (storedLayoutKey(before) !== storedLayoutKey(doc)) this.toStored();
    this.emit("document");
  }

  /** Back to the stored layout: one undoable step. */
  reset(): void {
    const before = this.snapshot();
    this.toStored();
    this.record("reset the room layout", before);
  }

  /** Back to the stored layout, not a step of its own (the caller records it). */
  showStored(): void {
    this.toStored();
  }

  /** The corners now, for undo and redo (a copy). */
  snapshot(): LayoutState {
    return copyState({
      corners: this.corners,
      used: this.used,
      unseenDistance: this.unseenDistance,
      cameraHeightM: this.cameraHeightM,
    });
  }

  /** Put a state back (undo, redo, a recovered draft): the room is re-fitted at once. */
  applyState(state: LayoutState): void {
    this.dragStart = null;
    this.setState(copyState(state));
    this.settle();
  }

  /**
   * A drag begins on corner `index`: returns where the corner is (a corner the fit did not
   * use is pinned where the fitted room puts it), or null when it has no handle.
   */
  beginDrag(index: number): Point2 | null {
    const handle = this.handles().find((h) => h.index === index);
    if (!handle) return null;
    this.dragStart = { index, from: handle.point, state: this.snapshot() };
    if (!handle.pinned) {
      this.used[index] = true;
      this.corners[index] = [handle.point[0], handle.point[1]];
      this.version++;
    }
    return handle.point;
  }

  /** Move a corner; the room is re-fitted on the next animation frame. */
  moveCorner(index: number, point: Point2): void {
    if (!this.used[index]) return;
    this.corners[index] = point;
    this.moved = true;
    this.version++;
    this.frame ||= requestAnimationFrame(() => {
      this.frame = 0;
      this.refit();
    });
  }

  /** The drag ends: the room is fitted to the last position, and the drag is one step. */
  endDrag(): void {
    const start = this.dragStart;
    if (!start) return;
    this.dragStart = null;
    const { index, from, state } = start;
    if (samePoint(this.corners[index], from)) {
      // A click: a corner the fit placed is not pinned by it.
      if (state.used[index]) this.refit();
      else this.applyState(state);
      return;
    }
    this.settle();
    this.record(`move the room's ${cornerName(index)}`, state);
  }

  /** Fit the room to the corners now (also what a pending animation frame does). */
  refit(): void {
    this.cancelFrame();
    const camera = this.doc.scene.camera;
    if (!camera) return;
    const start = performance.now();
    try {
      const fit = fitRoom(camera.K, this.fitCorners(), this.cameraHeight, {
        unseenWallDistance: this.unseenDistance,
        start: this.live ?? this.basisRoom(),
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
      camera_height_m: this.cameraHeightM,
    };
  }

  /** Tell the history about a finished step that started from `before`. */
  private record(label: string, before: LayoutState): void {
    const after = this.snapshot();
    if (!sameLayout(before, after)) this.onStep?.(label, before, after);
  }

  private setState(state: LayoutState): void {
    this.corners = state.corners;
    this.used = state.used;
    this.unseenDistance = state.unseenDistance;
    this.cameraHeightM = state.cameraHeightM ?? null;
    this.version++;
  }

  /** The stored layout's corners and room. `pinned`: corners to keep using (if known). */
  private toStored(pinned: readonly boolean[] = []): void {
    this.dragStart = null;
    if (!this.editing) this.starter = null;
    this.setState(this.storedState(pinned));
    this.showStoredRoom();
  }

  /** Fit the room to the corners, or show the stored room when they are the stored ones. */
  private settle(): void {
    this.moved = !sameLayout(this.snapshot(), this.storedState(this.used));
    if (this.moved) this.refit();
    else this.showStoredRoom();
  }

  /** Show the stored room (the corners give the stored layout). */
  private showStoredRoom(): void {
    this.cancelFrame();
    this.live = this.basisRoom();
    this.error = null;
    this.moved = false;
    this.fitTimes.length = 0;
    this.emit("fit");
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
   * `pinned`: corners the user dragged before, used too.
   */
  private storedState(pinned: readonly boolean[] = []): LayoutState {
    const stored = this.starter?.corners2d ?? this.doc.scene.layout?.corners_2d ?? [];
    const corners = Array.from({ length: 8 }, (_, i): Corner => {
      const c = stored[i];
      return c ? [c[0], c[1]] : null;
    });
    const room = this.basisRoom()?.room ?? null;
    const choose = (used: boolean[]) => {
      const known = corners.map((c, i) => (used[i] ? c : null));
      const wall = unseenWall(known);
      const distance = wall && room ? wallDistance(room, wall) : null;
      const usable =
        (distance === null || distance > 0) && cornerCoverageProblem(known, distance) === null;
      return { used, distance, usable };
    };
    const visible = choose(corners.map((c, i) => c !== null && (this.inView(c) || !!pinned[i])));
    const chosen = visible.usable ? visible : choose(corners.map((c) => c !== null));
    return { corners, used: chosen.used, unseenDistance: chosen.distance, cameraHeightM: null };
  }

  /** The room the corners start from: the stored one, else the starting room, if any. */
  private basisRoom(): LiveRoom | null {
    const starter = this.starter;
    if (starter === null) return storedRoom(this.doc);
    const { pitchDeg, rollDeg, room, corners3d } = starter;
    return { pitchDeg, rollDeg, room, corners3d };
  }

  private emit(change: LayoutChange): void {
    for (const listener of this.listeners) listener(change);
  }
}
