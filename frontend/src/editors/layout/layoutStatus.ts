// What the layout bar's status line says: a message of the bar's own (a save, a failure), why
// the layout cannot be edited, a save that failed, or the room being dragged.
import type { LayoutDraft } from "../../state/layoutDraft";
import type { SaveState } from "../../state/sceneSession";

export interface StatusLine {
  text: string;
  alert: boolean;
}

/** Ceilings people live under, and the narrowest room side, in metres. */
const CEILING_M: readonly [number, number] = [2.0, 5.0];
const NARROWEST_M = 1.2;
/** Longer than this, a room is a hall or a corner dropped on a far line (a window's edge). */
const LONGEST_M = 12;
/** The least headroom above the camera (a photo is taken at eye or chest height). */
const HEADROOM_M = 0.3;

/**
 * What the dragged room has that rooms do not: a corner dropped on the wrong line (a ceiling
 * corner on a picture's edge) makes such a room, and it is saved like any other, so the bar
 * says so while the person can still drag it back.
 */
export function roomDoubts(size: readonly number[], cameraHeight: number): string[] {
  const [depth = 0, height = 0, width = 0] = size;
  const doubts: string[] = [];
  if (height < CEILING_M[0] || height > CEILING_M[1]) {
    doubts.push(`a ceiling ${height.toFixed(2)} m high`);
  }
  if (height - cameraHeight < HEADROOM_M) {
    doubts.push(
      `${Math.max(0, height - cameraHeight).toFixed(2)} m from the camera to the ceiling`,
    );
  }
  if (Math.min(depth, width) < NARROWEST_M) {
    doubts.push(`a room ${Math.min(depth, width).toFixed(2)} m across`);
  }
  if (Math.max(depth, width) > LONGEST_M) {
    doubts.push(`a room ${Math.max(depth, width).toFixed(2)} m long`);
  }
  return doubts;
}

export function layoutStatus(
  draft: LayoutDraft,
  saveState: SaveState,
  message: StatusLine | null,
): StatusLine {
  if (message) return message;
  if (!draft.available) {
    return {
      text: draft.hasStoredRoom
        ? "The stored room has no corner in front of the camera to drag."
        : "No room layout yet: the photo has no camera intrinsics (run the pipeline first).",
      alert: false,
    };
  }
  if (draft.error !== null)
    return {
      text:
        `No room from these corners: ${draft.error}. The room shown is the last one that fit; ` +
        "move the corner back, or Reset.",
      alert: true,
    };
  if (draft.dirty && (saveState.kind === "error" || saveState.kind === "conflict")) {
    return { text: `Not saved: ${saveState.message} Your corners are kept.`, alert: true };
  }
  const live = draft.live;
  if (!draft.editing && !draft.hasStoredRoom && !draft.dirty) {
    return {
      text: `No room layout yet: "Edit layout" puts up a room to start from.`,
      alert: false,
    };
  }
  if (!live) return { text: "", alert: false };
  const [depth, height, width] = live.room.size.map((s) => s.toFixed(2));
  const camera = `camera ${draft.cameraHeight.toFixed(2)} m high, pitch ${live.pitchDeg.toFixed(1)}°, roll ${live.rollDeg.toFixed(1)}°`;
  const room = `room ${depth} × ${width} m, ${height} m high; ${camera}`;
  const doubts = roomDoubts(live.room.size, draft.cameraHeight);
  // The saved room's figures before editing too (the line is there already when editing
  // starts, so the photo below does not move), with what a reviewer should doubt in them.
  if (!draft.editing) {
    const check = doubts.length ? ` Check its corners: this gives ${doubts.join(", ")}.` : "";
    return { text: `The ${room}.${check}`, alert: false };
  }
  if (draft.starting) {
    return {
      text: `A room to start from: drag its yellow corners onto the photo's room corners (saved once one moves). ${room}`,
      alert: false,
    };
  }
  const doubt = doubts.length
    ? ` Is a corner on the wrong line? This gives ${doubts.join(", ")}.`
    : "";
  return {
    text: (draft.dirty ? `Moved (not saved): ${room}` : `Drag the yellow corners. ${room}`) + doubt,
    alert: doubts.length > 0,
  };
}
