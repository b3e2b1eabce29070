// Unsaved edits kept in localStorage until the server confirms them, so a closed tab or a
// crash loses nothing: the next visit to the scene offers them back.
import type { LayoutState } from "./layoutDraft";
import type { Edit } from "./supportGraph";

export interface Draft {
  sceneId: string;
  /** The revision the edits were made on. */
  baseRevision: number;
  edits: Edit[];
  /** The room layout's corners, when they were moved and not saved. */
  layout?: LayoutState | null;
  /** ISO time of the last change. */
  savedAt: string;
}

/** Whether a draft holds anything unsaved. */
const hasChanges = (draft: Draft) => draft.edits.length > 0 || !!draft.layout;

const key = (sceneId: string) => `holiscene.draft.${sceneId}`;
const recoveredKey = (sceneId: string) => `holiscene.draft.${sceneId}.recovered`;

function browserStorage(): Storage | null {
  try {
    return typeof localStorage === "undefined" ? null : localStorage;
  } catch {
    return null; // storage refused (private mode): drafts last for the page only
  }
}

function isDraft(value: unknown): value is Draft {
  if (!value || typeof value !== "object") return false;
  const d = value as Partial<Draft>;
  return (
    typeof d.sceneId === "string" &&
    typeof d.baseRevision === "number" &&
    Array.isArray(d.edits) &&
    (d.layout == null || isLayoutState(d.layout))
  );
}

function isLayoutState(value: unknown): value is LayoutState {
  const l = value as Partial<LayoutState>;
  const point = (c: unknown) =>
    c === null || (Array.isArray(c) && c.length === 2 && c.every(Number.isFinite));
  return (
    Array.isArray(l.corners) &&
    l.corners.length === 8 &&
    l.corners.every(point) &&
    Array.isArray(l.used) &&
    l.used.length === 8 &&
    (l.unseenDistance === null || typeof l.unseenDistance === "number") &&
    (l.cameraHeightM == null || (typeof l.cameraHeightM === "number" && l.cameraHeightM > 0))
  );
}

export class DraftStore {
  constructor(private readonly storage: Storage | null = browserStorage()) {}

  private read(name: string): Draft | null {
    try {
      const value: unknown = JSON.parse(this.storage?.getItem(name) ?? "null");
      return isDraft(value) && hasChanges(value) ? value : null;
    } catch {
      return null;
    }
  }

  private write(name: string, draft: Draft | null): void {
    try {
      if (draft && hasChanges(draft)) this.storage?.setItem(name, JSON.stringify(draft));
      else this.storage?.removeItem(name);
    } catch {
      // full or refused: the edits still live in the page
    }
  }

  /** Keep the scene's unsaved edits (none: forget them). */
  save(draft: Draft): void {
    this.write(key(draft.sceneId), draft);
  }

  load(sceneId: string): Draft | null {
    return this.read(key(sceneId));
  }

  /**
   * The edits a previous visit left unsaved, set aside for the user to restore or discard
   * (so the new visit's own edits cannot overwrite them before they decide).
   */
  takeForRecovery(sceneId: string): Draft | null {
    const earlier = this.read(recoveredKey(sceneId));
    const latest = this.read(key(sceneId));
    const merged = mergeDrafts(earlier, latest);
    this.write(recoveredKey(sceneId), merged);
    this.write(key(sceneId), null);
    return merged;
  }

  /** The user restored or discarded the set-aside edits. */
  clearRecovered(sceneId: string): void {
    this.write(recoveredKey(sceneId), null);
  }
}

/** Both drafts' edits, one per object (and the layout), the later draft's winning. */
function mergeDrafts(earlier: Draft | null, later: Draft | null): Draft | null {
  if (!earlier || !later) return later ?? earlier;
  const edits = new Map<string, Edit>();
  for (const edit of [...earlier.edits, ...later.edits]) {
    edits.delete(edit.child);
    edits.set(edit.child, edit);
  }
  return { ...later, edits: [...edits.values()], layout: later.layout ?? earlier.layout ?? null };
}
