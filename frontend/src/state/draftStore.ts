// Unsaved edits kept in localStorage until the server confirms them, so a closed tab or a
// crash loses nothing: the next visit to the scene offers them back. An object action the
// server did not take (object edits are not drafts: each is saved at once) is kept beside them
// until it is saved or the person drops it. Each person's drafts are their own: whoever logs
// in next in the same browser is not offered them (nor could save them under their name).

import { browserStorage } from "./browserStorage";
import { getCurrentUser } from "./currentUser";
import type { LayoutState } from "./layoutDraft";
import type { ObjectEdit } from "./objectEditor";
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

/** An object action that failed (Retry and Discard shown), as the next visit offers it again. */
export interface FailedObjectAction {
  label: string;
  /** Why it was not saved. */
  message: string;
  /** The edits as they were to be sent (an undo's are its restore_object edits). */
  edits: ObjectEdit[];
  /** ISO time it failed. */
  failedAt: string;
  /** The revision it was made on: a Retry tells whether others changed its objects since. */
  madeOn?: number;
  /** A new object added under a stand-in class (its class was still being picked): once a
   * Retry adds it, the person is asked its class. */
  classToPick?: string;
}

/** Whether a draft holds anything unsaved. */
const hasChanges = (draft: Draft) => draft.edits.length > 0 || !!draft.layout;

/** Where a scene's drafts are kept: per person (null: as stored before drafts had owners). */
function keysOf(owner: string | null, sceneId: string) {
  const base =
    owner === null
      ? `holiscene.draft.${sceneId}`
      : `holiscene.drafts/${encodeURIComponent(owner)}/${sceneId}`;
  return {
    draft: base,
    recovered: `${base}.recovered`,
    failed: `${base}.failedObjectAction`,
  };
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

function isFailedObjectAction(value: unknown): value is FailedObjectAction {
  if (!value || typeof value !== "object") return false;
  const a = value as Partial<FailedObjectAction>;
  const isEdit = (e: unknown) => {
    const edit = e as { kind?: unknown; id?: unknown; from_revision?: unknown } | null;
    if (!edit || typeof edit.kind !== "string") return false;
    // A revert names a revision, every other object edit an object.
    return edit.kind === "restore_scene"
      ? typeof edit.from_revision === "number"
      : typeof edit.id === "string";
  };
  return (
    typeof a.label === "string" &&
    typeof a.message === "string" &&
    typeof a.failedAt === "string" &&
    Array.isArray(a.edits) &&
    a.edits.length > 0 &&
    a.edits.every(isEdit) &&
    (a.classToPick === undefined || typeof a.classToPick === "string")
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
  /** `owner`: whose drafts these are (the signed-in person when the scene was opened). */
  constructor(
    private readonly storage: Storage | null = browserStorage(),
    readonly owner: string | null = getCurrentUser()?.name ?? null,
  ) {}

  private keys(sceneId: string) {
    return keysOf(this.owner, sceneId);
  }

  /** The keys of drafts stored before they had owners: read once, by whoever comes first. */
  private legacyKeys(sceneId: string) {
    return this.owner === null ? null : keysOf(null, sceneId);
  }

  /** The value stored under `name` if it is one (null: none, or not one). */
  private readAs<T>(name: string, valid: (value: unknown) => value is T): T | null {
    try {
      const value: unknown = JSON.parse(this.storage?.getItem(name) ?? "null");
      return valid(value) ? value : null;
    } catch {
      return null;
    }
  }

  /** Store `value` under `name` (null: remove it). */
  private store(name: string, value: object | null): void {
    try {
      if (value) this.storage?.setItem(name, JSON.stringify(value));
      else this.storage?.removeItem(name);
    } catch {
      // full or refused: what it held still lives in the page
    }
  }

  private read(name: string): Draft | null {
    const draft = this.readAs(name, isDraft);
    return draft && hasChanges(draft) ? draft : null;
  }

  private write(name: string, draft: Draft | null): void {
    this.store(name, draft && hasChanges(draft) ? draft : null);
  }

  /** Keep the scene's unsaved edits (none: forget them). */
  save(draft: Draft): void {
    this.write(this.keys(draft.sceneId).draft, draft);
  }

  load(sceneId: string): Draft | null {
    return this.read(this.keys(sceneId).draft);
  }

  /**
   * The edits a previous visit left unsaved, set aside for the user to restore or discard
   * (so the new visit's own edits cannot overwrite them before they decide).
   */
  takeForRecovery(sceneId: string): Draft | null {
    const keys = this.keys(sceneId);
    const legacy = this.legacyKeys(sceneId);
    let merged: Draft | null = null;
    for (const name of [legacy?.recovered, legacy?.draft, keys.recovered, keys.draft])
      if (name) merged = mergeDrafts(merged, this.read(name));
    this.write(keys.recovered, merged);
    this.write(keys.draft, null);
    if (legacy) {
      this.write(legacy.recovered, null);
      this.write(legacy.draft, null);
    }
    return merged;
  }

  /** The user restored or discarded the set-aside edits. */
  clearRecovered(sceneId: string): void {
    this.write(this.keys(sceneId).recovered, null);
  }

  /** Keep the scene's failed object action (null: it was saved or dropped). */
  saveFailedAction(sceneId: string, action: FailedObjectAction | null): void {
    this.store(this.keys(sceneId).failed, action);
  }

  loadFailedAction(sceneId: string): FailedObjectAction | null {
    const own = this.readAs(this.keys(sceneId).failed, isFailedObjectAction);
    const legacy = this.legacyKeys(sceneId);
    if (own || !legacy) return own;
    // One kept before actions had owners becomes this person's.
    const kept = this.readAs(legacy.failed, isFailedObjectAction);
    if (kept) this.saveFailedAction(sceneId, kept);
    this.store(legacy.failed, null);
    return kept;
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
