// Object edits (add, remove, class, box, mask): unlike support edits they are not kept as
// unsaved drafts; every action is one POST /api/scenes/{id}/edits on the loaded revision, and the
// revision the server answers becomes the loaded one (session.adopt). Undo of an action is one
// restore_object per object it touched, naming the revision before it; redo names the revision
// it made (revisions never change, so both stay exact). Actions run one after another. On a
// conflict (someone saved first) the latest revision is loaded and the action sent again on top
// of it when the objects it changes still exist; otherwise it stays, with Retry and Discard, so
// nothing a person did is silently lost: it is kept in localStorage too (the session's
// DraftStore) until saved or dropped, and a later visit offers it again. One that failed on
// the way (the server unreachable or failing) is also sent again by itself every few seconds.
import type {
  AddObject,
  EditRequest,
  RemoveObject,
  RestoreObject,
  RestoreScene,
  RevisionInfo,
  SceneDocument,
  SceneObject,
  SetBbox,
  SetClass,
  SetMask,
} from "@holiscene/schema";
import { api } from "../api/client";
import { ApiError, ConflictError, errorText } from "../api/errors";
import { formatTime } from "../dom";
import { freshIds } from "../views/scene/detectionOffers";
import { getAuthor } from "./author";
import { HistoryKeeper } from "./editHistory";
import { lockText } from "./editLock";
import { newObjectNotes } from "./newObjectNotes";
import { predictDocument } from "./objectPrediction";
import { saveDone, trackSave } from "./savesInFlight";
import type { SceneSession } from "./sceneSession";
import type { Undoable } from "./undoOrder";

/** The contract's AddObject, its defaults left out (no mask: the server cuts one; no score). */
export type NewObject = Omit<AddObject, "mask" | "score"> &
  Partial<Pick<AddObject, "mask" | "score">>;

export type ObjectEdit =
  | NewObject
  | RemoveObject
  | SetClass
  | SetBbox
  | SetMask
  | RestoreObject
  | RestoreScene;

/** What an action that restored the whole scene touched: no object id looks like it. */
export const WHOLE_SCENE = "*scene";

/** What the editor is doing: nothing (with what the last action did), or saving an action. */
export type ObjectEditStatus =
  | { kind: "idle"; message: string | null; error: boolean }
  | { kind: "busy"; label: string };

/** An action that could not be saved, kept until the person retries or drops it. */
export interface FailedAction {
  label: string;
  message: string;
  /** Sent again by itself soon (it failed on the way, not by the server's refusal). */
  retrying?: boolean;
}

export const OBJECT_RETRY_MS = 5000;

/** Whether sending again may succeed without any change: the request never got an answer, or
 * the server failed (5xx); a refusal (4xx) would only be refused again. */
function failedOnTheWay(error: unknown): boolean {
  return error instanceof ApiError ? error.status >= 500 : error instanceof TypeError;
}

/** Sends one request of edits on a revision; the API by default (tests give their server). */
export type PostEdits = (
  sceneId: string,
  baseRevision: number,
  author: string,
  edits: ObjectEdit[],
) => Promise<SceneDocument>;

/**
 * An edit as the API takes it: as it is (the contract's types list a new object's mask and
 * score as always present, but the API takes them left out, as null).
 */
const wire = (edit: ObjectEdit) => edit as EditRequest["edits"][number];

const postToApi: PostEdits = (sceneId, baseRevision, author, edits) => {
  const [first, ...rest] = edits.map(wire);
  if (!first) return Promise.reject(new Error("no edits to send"));
  return api.postEdits(sceneId, { base_revision: baseRevision, author, edits: [first, ...rest] });
};

/** The objects an action names, each once, in order (WHOLE_SCENE for a restored scene). */
export function touchedIds(edits: readonly ObjectEdit[]): string[] {
  return [...new Set(edits.map((edit) => (edit.kind === "restore_scene" ? WHOLE_SCENE : edit.id)))];
}

/** `ids` for a person to read ("the scene" for WHOLE_SCENE). */
export function touchedText(ids: readonly string[]): string {
  return ids.map((id) => (id === WHOLE_SCENE ? "the scene" : id)).join(", ");
}

/** What an undo must find unchanged: the object, or for WHOLE_SCENE all a revert puts back. */
function touchedState(doc: SceneDocument, id: string): string {
  if (id !== WHOLE_SCENE) return canonical(doc.scene.objects?.find((o) => o.id === id) ?? null);
  const { objects, supports, layout, camera, removed_by_person } = doc.scene;
  return canonical({ objects, supports, layout, camera, removed_by_person });
}

/** The ids among `ids` whose object differs between two revisions (or is in only one). */
export function objectsChanged(
  ids: readonly string[],
  from: SceneDocument,
  to: SceneDocument,
): string[] {
  return ids.filter((id) => touchedState(from, id) !== touchedState(to, id));
}

/**
 * The edits that put the objects back as they were in `revision` (or remove them); the whole
 * scene when the action restored it.
 */
export function restoreEdits(
  ids: readonly string[],
  revision: number,
): (RestoreObject | RestoreScene)[] {
  if (ids.includes(WHOLE_SCENE)) return [{ kind: "restore_scene", from_revision: revision }];
  return ids.map((id) => ({ kind: "restore_object", id, from_revision: revision }));
}

export type Rebased =
  | { edits: ObjectEdit[]; renamed: [string, string][] }
  | { edits: null; missing: string[] };

/**
 * An action made on an older revision, for `objects` (a newer one's): a new object whose id was
 * taken meanwhile gets a free one (the action's later edits follow it); an action changing an
 * object that is gone cannot be applied (restore_object always can: it may bring one back).
 */
export function rebaseEdits(
  edits: readonly ObjectEdit[],
  objects: readonly SceneObject[],
): Rebased {
  const present = new Set(objects.map((o) => o.id));
  const renamed = new Map<string, string>();
  const missing: string[] = [];
  const out: ObjectEdit[] = [];
  for (const edit of edits) {
    if (edit.kind === "restore_scene") {
      out.push(edit); // always applies: the server restores the revision as a whole
      continue;
    }
    const id = renamed.get(edit.id) ?? edit.id;
    if (edit.kind === "add_object") {
      const free = present.has(id)
        ? (freshIds(
            [...present].map((i) => ({ id: i })),
            1,
          )[0] ?? id)
        : id;
      if (free !== id) renamed.set(edit.id, free);
      present.add(free);
      out.push({ ...edit, id: free });
      continue;
    }
    if (edit.kind !== "restore_object" && !present.has(id)) {
      if (!missing.includes(id)) missing.push(id);
      continue;
    }
    if (edit.kind === "remove_object") present.delete(id);
    if (edit.kind === "restore_object") present.add(id);
    out.push({ ...edit, id });
  }
  return missing.length > 0 ? { edits: null, missing } : { edits: out, renamed: [...renamed] };
}

/** Who saved the revisions after `before` up to `latest` ("Someone" if that is unknown). */
function authorsSince(
  revisions: readonly Pick<RevisionInfo, "number" | "author">[],
  before: number,
  latest: number,
): string {
  const names = revisions
    .filter((r) => r.number > before && r.number <= latest)
    .map((r) => r.author);
  return [...new Set(names)].join(", ") || "Someone";
}

/** JSON with keys in order and empty (null or absent) fields left out, to compare edits. */
function canonical(value: unknown): string {
  return JSON.stringify(value, (_key, v: unknown) => {
    if (v === null || typeof v !== "object" || Array.isArray(v)) return v;
    const entries = Object.entries(v as Record<string, unknown>).filter(([, x]) => x != null);
    return Object.fromEntries(entries.sort(([a], [b]) => (a < b ? -1 : a > b ? 1 : 0)));
  });
}

/**
 * The revision after `before` that holds exactly these edits: an earlier try of the action
 * that the server saved though its answer never reached the page (a lost connection). Sending
 * it again on top would add its new objects twice, under other ids.
 */
export function savedAlready(
  revisions: readonly Pick<RevisionInfo, "number" | "edits">[],
  before: number,
  edits: readonly ObjectEdit[],
): number | null {
  const wanted = canonical(edits);
  const found = revisions.find(
    (r) => r.number > before && r.edits != null && canonical(r.edits) === wanted,
  );
  return found?.number ?? null;
}

const capital = (text: string) => text.charAt(0).toUpperCase() + text.slice(1);

/** What one sent action did: the revisions before and after it, and the edits as sent. */
interface Sent {
  before: number;
  after: number;
  edits: ObjectEdit[];
}

/** Its history's steps: the objects one action touched, keyed by id, with the revisions around it. */
export class ObjectEditor extends HistoryKeeper<number> implements Undoable {
  status: ObjectEditStatus = { kind: "idle", message: null, error: false };
  failure: FailedAction | null = null;

  private readonly listeners = new Set<() => void>();
  private queue: Promise<unknown> = Promise.resolve();
  private waiting = 0;
  /** Sends the failed action again; true once saved. */
  private retryFailed: (() => Promise<boolean>) | null = null;
  /** The failed action's edits (null: none failed, or it was an undo or redo). */
  private failedEdits: ObjectEdit[] | null = null;
  /** The revision the failed action was made on (null: not known, kept before this was). */
  private failedMadeOn: number | null = null;
  /** The failed action adds this object under a stand-in class: name it once added. */
  private failedClassToPick: string | null = null;
  /** What a Retry added under a stand-in class, for the page to ask its class. */
  private objectToName: SceneObject | null = null;
  /** The person was told someone changed the failed action's objects since: the next Retry
   * puts theirs on top. */
  private overwriteTold = false;
  /** Ids of new objects in actions not saved yet. */
  private readonly reserved = new Set<string>();
  /** Revisions this page had loaded, by number (an undo shows the one it restores at once). */
  private readonly seen = new Map<number, SceneDocument>();
  private retryTimer: ReturnType<typeof setTimeout> | null = null;

  constructor(
    readonly session: SceneSession,
    private readonly options: { author?: () => string; post?: PostEdits; retryMs?: number } = {},
  ) {
    super();
    const kept = session.drafts.loadFailedAction(session.sceneId);
    if (kept) {
      // Why it failed then, said as then: the server may well answer now.
      const when = formatTime(kept.failedAt);
      this.failure = {
        label: kept.label,
        message: `Not saved on your last visit (${when}): ${kept.message}. Retry sends it now.`,
      };
      this.failedEdits = [...kept.edits];
      this.failedMadeOn = kept.madeOn ?? null;
      this.failedClassToPick = kept.classToPick ?? null;
      this.retryFailed = () => this.apply(kept.edits, kept.label);
    }
  }

  /** Stop sending a failed action again by itself (the page is left; it stays in the drafts). */
  dispose(): void {
    this.cancelRetry();
  }

  /** Told after every change of status, failure or history. */
  subscribe(listener: () => void): () => void {
    this.listeners.add(listener);
    return () => this.listeners.delete(listener);
  }

  /** Whether an action is being saved or waits its turn. */
  get busy(): boolean {
    return this.waiting > 0;
  }

  /**
   * `count` ids for new objects: free in the scene and not given to an action still waiting
   * (two boxes drawn quickly get two ids).
   */
  newObjectIds(count: number): string[] {
    const used = [...this.session.objects.map((o) => o.id), ...this.reserved];
    return freshIds(
      used.map((id) => ({ id })),
      count,
    );
  }

  /** Save one action (e.g. "add chair d3"); true once the server has it. */
  apply(edits: readonly ObjectEdit[], label: string): Promise<boolean> {
    const added = edits.filter((e) => e.kind === "add_object").map((e) => e.id);
    for (const id of added) this.reserved.add(id);
    return this.enqueue(async () => {
      const sent = await this.send(label, edits, () => this.apply(edits, label), true);
      for (const id of added) this.reserved.delete(id);
      if (!sent) return false;
      this.history.record({
        label,
        changes: touchedIds(sent.edits).map((key) => ({
          key,
          before: sent.before,
          after: sent.after,
        })),
      });
      this.changed();
      return true;
    });
  }

  /** Take back the last action; resolves to its label (null: nothing to undo, or it failed). */
  undo(): Promise<string | null> {
    return this.step("undo");
  }

  /** Do the last undone action again; resolves to its label (null: nothing, or it failed). */
  redo(): Promise<string | null> {
    return this.step("redo");
  }

  /**
   * Undo: put the objects of the last action back as in the revision before it; redo: as in
   * the revision it made. One that fails stays the one to undo (or redo).
   */
  private step(way: "undo" | "redo"): Promise<string | null> {
    const history = this.history;
    const [take, giveBack] =
      way === "undo"
        ? [() => history.undo(), () => history.redo()]
        : [() => history.redo(), () => history.undo()];
    return this.enqueue(async () => {
      const entry = take();
      if (!entry) return null;
      const ids = entry.changes.map((c) => c.key);
      const first = entry.changes[0];
      const revision = (way === "undo" ? first?.before : first?.after) ?? 0;
      // An undo puts back the revision before the action: if someone changed the objects
      // since the action, that would silently throw their change away.
      const left = way === "undo" && first ? this.seen.get(first.after) : undefined;
      const since = left ? objectsChanged(ids, left, this.session.doc) : [];
      if (since.length > 0) {
        giveBack();
        this.refuseOverwrite(`${way} ${entry.label}`, since);
        return null;
      }
      const sent = await this.send(
        `${way} ${entry.label}`,
        restoreEdits(ids, revision),
        async () => (await this.step(way)) !== null,
        false,
      );
      if (!sent) giveBack();
      this.changed();
      return sent ? entry.label : null;
    });
  }

  /**
   * The object `edits` added as `id` under a stand-in class, as the revision holds it (the id
   * may have been taken meanwhile and another given); null when it is not in the scene.
   */
  private addedObject(edits: readonly ObjectEdit[], id: string): SceneObject | null {
    const add = edits.find(
      (edit): edit is AddObject => edit.kind === "add_object" && edit.id === id,
    );
    if (!add) return null;
    const objects = this.session.objects;
    const same = (o: SceneObject) =>
      o.class === add.class && o.bbox.every((v, i) => Math.abs(v - (add.bbox[i] ?? v)) < 0.5);
    const own = objects.find((o) => o.id === add.id);
    return own && same(own) ? own : (objects.find(same) ?? null);
  }

  /** The object the last Retry added whose class is still to be picked, once (null: none). */
  takeObjectToName(): SceneObject | null {
    const object = this.objectToName;
    this.objectToName = null;
    return object;
  }

  /**
   * Send the failed action again (on the latest revision); true once saved. If someone else
   * changed its objects since it was made, the first Retry only says so (putting it on top
   * would silently replace their change); the next one sends it.
   */
  async retry(): Promise<boolean> {
    const failed = this.failure;
    const again = this.retryFailed;
    const edits = this.failedEdits;
    const madeOn = this.failedMadeOn;
    const classToPick = this.failedClassToPick;
    if (!failed || !again) return false;
    if (edits && madeOn !== null && !this.overwriteTold) {
      const since = await this.changedByOthers(edits, madeOn);
      if (since) {
        this.overwriteTold = true;
        this.cancelRetry();
        this.failure = {
          label: failed.label,
          message:
            `${since.who} changed ${touchedText(since.ids)} since you made this change. ` +
            "Retry again to put yours on top of theirs, or Discard to keep theirs.",
        };
        this.changed();
        return false;
      }
    }
    this.setFailure(null, null);
    // Stored until saved: a tab closed while it is being sent loses nothing.
    const saved = await again();
    if (saved && this.failure === null) this.keepFailed(null);
    if (saved && edits && classToPick) this.objectToName = this.addedObject(edits, classToPick);
    // Not sent at all (the scene is read only now): still offered, for the person to retry.
    if (!saved && this.failure === null) {
      this.setFailure({ label: failed.label, message: failed.message }, again);
      this.failedEdits = edits;
      this.failedMadeOn = madeOn;
      this.failedClassToPick = classToPick;
    }
    return saved;
  }

  /** The objects of `edits` that others changed since revision `madeOn`, and who (null: none,
   * or it cannot be told). */
  private async changedByOthers(
    edits: readonly ObjectEdit[],
    madeOn: number,
  ): Promise<{ ids: string[]; who: string } | null> {
    const session = this.session;
    if (session.doc.revision <= madeOn) return null;
    try {
      const me = (this.options.author ?? getAuthor)();
      const revisions = await api.listRevisions(session.sceneId);
      const latest = session.doc.revision;
      const others = revisions.filter(
        (r) => r.number > madeOn && r.number <= latest && r.author !== me,
      );
      if (others.length === 0) return null;
      const made = this.seen.get(madeOn) ?? (await api.getRevision(session.sceneId, madeOn));
      const ids = objectsChanged(touchedIds(edits), made, session.doc);
      return ids.length > 0 ? { ids, who: authorsSince(others, madeOn, latest) } : null;
    } catch {
      return null; // unknown: sent as before (a conflict on the way is still caught)
    }
  }

  /** Drop the failed action (the person chose to). */
  discardFailed(): void {
    const label = this.failure?.label;
    this.setFailure(null, null);
    this.keepFailed(null);
    if (label) this.setStatus({ kind: "idle", message: `Dropped: ${label}.`, error: false });
  }

  private setFailure(failure: FailedAction | null, retry: (() => Promise<boolean>) | null): void {
    if (failure === null) {
      this.failedEdits = null;
      this.failedMadeOn = null;
      this.failedClassToPick = null;
      this.overwriteTold = false;
    }
    this.cancelRetry();
    this.failure = failure;
    this.retryFailed = retry;
    this.changed();
  }

  /** Keep the failed action in the scene's drafts (null: forget it). */
  private keepFailed(
    action: { label: string; message: string; edits: ObjectEdit[]; madeOn?: number } | null,
  ): void {
    const kept = action && { ...action, failedAt: new Date().toISOString() };
    this.session.drafts.saveFailedAction(this.session.sceneId, kept);
  }

  private enqueue<T>(task: () => Promise<T>): Promise<T> {
    this.waiting++;
    const run = async () => {
      try {
        return await task();
      } finally {
        this.waiting--;
        this.changed();
      }
    };
    const next = this.queue.then(run, run);
    this.queue = next.catch(() => undefined);
    trackSave(next);
    return next;
  }

  /**
   * Post `edits` on the loaded revision and adopt the answer. After a conflict, load the
   * latest revision and send them once more on top of it if they still apply.
   */
  private async send(
    label: string,
    edits: readonly ObjectEdit[],
    retry: () => Promise<boolean>,
    isAction: boolean,
  ): Promise<Sent | null> {
    const session = this.session;
    const madeOn = session.doc.revision; // what the person saw when they made it
    const lock = session.lock;
    if (lock) {
      this.setStatus({ kind: "idle", message: lockText(lock), error: true });
      return null;
    }
    this.setStatus({ kind: "busy", label });
    let shown: SceneDocument | null = null; // the revision under a prediction
    try {
      await saveDone(session);
      const before = session.doc.revision;
      this.remember(session.doc);
      // A new object's id taken since the action was made (by a retried one) gets a free one;
      // an edit of an object that is gone goes as it is, for the server to say why not.
      const sending = rebaseEdits(edits, session.objects).edits ?? [...edits];
      // Redraw now what the action will do; the server's answer replaces it.
      const predicted = predictDocument(session.doc, sending, (n) => this.seen.get(n));
      if (predicted) {
        shown = session.doc;
        session.adopt(predicted);
      }
      try {
        return this.adopt(label, before, sending, await this.post(before, sending), null);
      } catch (error) {
        if (!(error instanceof ConflictError) || error.currentRevision === null) throw error;
      }
      shown = null; // the reload below replaces the prediction
      await session.reloadLatest();
      const latest = session.doc.revision;
      const revisions = await api.listRevisions(session.sceneId).catch(() => []);
      const saved = savedAlready(revisions, before, sending);
      if (saved !== null) {
        this.remember(session.doc);
        const message = `${capital(label)}: already saved as revision ${saved} (its answer had not arrived).`;
        this.setStatus({ kind: "idle", message, error: false });
        return { before: saved - 1, after: saved, edits: sending };
      }
      const who = authorsSince(revisions, before, latest);
      const pageDoc = this.seen.get(before);
      const changed = pageDoc ? objectsChanged(touchedIds(edits), pageDoc, session.doc) : [];
      if (!isAction && changed.length > 0) {
        this.refuseOverwrite(label, changed, who);
        return null;
      }
      // A revert on top of a colleague's newer revision would throw all of it away: the
      // person looks at it first, and reverts again if they still want to.
      if (changed.includes(WHOLE_SCENE)) {
        const message =
          `Not done: ${label}. ${who} saved revision ${latest} meanwhile; reverting now would ` +
          "throw their change away. Look at it in the history, then revert again if you still want to.";
        this.setStatus({ kind: "idle", message, error: true });
        return null;
      }
      const rebased = rebaseEdits(edits, session.objects);
      if (rebased.edits === null) {
        const gone = rebased.missing.join(", ");
        this.fail(
          label,
          `${who} saved revision ${latest} meanwhile, and ${gone} ${rebased.missing.length === 1 ? "is" : "are"} ` +
            "no longer in the scene: your change was not applied.",
          edits,
          retry,
          isAction,
          madeOn,
        );
        return null;
      }
      const renames = rebased.renamed.map(([from, to]) => ` ${from} was taken: yours is ${to}.`);
      if (changed.length > 0) {
        renames.push(` Both of you changed ${touchedText(changed)}: yours is kept on top.`);
      }
      const note = `${who} saved revision ${latest} meanwhile; your change was applied on top.${renames.join("")}`;
      return this.adopt(label, latest, rebased.edits, await this.post(latest, rebased.edits), note);
    } catch (error) {
      if (shown) session.adopt(shown); // not saved: back to what the server has
      this.fail(label, errorText(error), edits, retry, isAction, madeOn, failedOnTheWay(error));
      return null;
    }
  }

  /** A revision this page has loaded: an undo or a revert naming it is shown at once. */
  remember(doc: SceneDocument): void {
    this.seen.set(doc.revision, doc);
    // The revisions an undo or redo may name: those of the last actions.
    if (this.seen.size > 100) this.seen.delete(this.seen.keys().next().value as number);
  }

  private adopt(
    label: string,
    before: number,
    edits: ObjectEdit[],
    doc: SceneDocument,
    note: string | null,
  ): Sent {
    this.session.adopt(doc);
    this.remember(doc);
    // No revision number: the save bar says which revision is the latest, and this line stays
    // up while later saves move it on.
    const message = (note ?? `${capital(label)}: saved.`) + newObjectNotes(edits, doc);
    this.setStatus({ kind: "idle", message, error: false });
    return { before, after: doc.revision, edits };
  }

  private post(baseRevision: number, edits: ObjectEdit[]): Promise<SceneDocument> {
    const post = this.options.post ?? postToApi;
    return post(this.session.sceneId, baseRevision, (this.options.author ?? getAuthor)(), edits);
  }

  /**
   * Keep an action that could not be saved, to retry or discard. One is kept (here and in the
   * drafts), so a second failed action joins the first (Retry sends both, in order) rather than
   * taking its place; an undo or redo that fails is no work of its own and never displaces one.
   */
  private fail(
    label: string,
    message: string,
    edits: readonly ObjectEdit[],
    retry: () => Promise<boolean>,
    isAction: boolean,
    madeOn: number,
    onTheWay = false,
  ): void {
    const earlier = this.failure;
    if (earlier && this.failedEdits) {
      if (!isAction) {
        this.setStatus({ kind: "idle", message: `Not saved: ${label}. ${message}`, error: true });
        return;
      }
      const both = [...this.failedEdits, ...edits];
      const together = `${earlier.label}, then ${label}`;
      const first = Math.min(this.failedMadeOn ?? madeOn, madeOn);
      const again = () => this.apply(both, together);
      this.setFailed(together, message, both, again, true, first, onTheWay);
      return;
    }
    this.setFailed(label, message, edits, retry, isAction, madeOn, onTheWay);
  }

  private setFailed(
    label: string,
    message: string,
    edits: readonly ObjectEdit[],
    retry: () => Promise<boolean>,
    isAction: boolean,
    madeOn: number,
    onTheWay: boolean,
  ): void {
    this.keepFailed({ label, message, edits: [...edits], madeOn });
    this.failure = onTheWay ? { label, message, retrying: true } : { label, message };
    this.failedEdits = isAction ? [...edits] : null;
    this.failedMadeOn = madeOn;
    this.retryFailed = retry;
    this.cancelRetry();
    if (onTheWay) {
      this.retryTimer = setTimeout(() => {
        this.retryTimer = null;
        void this.retry();
      }, this.options.retryMs ?? OBJECT_RETRY_MS);
    }
    this.setStatus({ kind: "idle", message: null, error: false });
  }

  private cancelRetry(): void {
    if (this.retryTimer !== null) clearTimeout(this.retryTimer);
    this.retryTimer = null;
  }

  /** An undo or redo not sent: it would overwrite what someone changed since. */
  private refuseOverwrite(label: string, ids: readonly string[], who = "Someone"): void {
    const message =
      `Not done: ${label}. ${who} changed ${touchedText(ids)} since; undoing would throw that ` +
      "change away. Change the object by hand instead.";
    this.setStatus({ kind: "idle", message, error: true });
  }

  private setStatus(status: ObjectEditStatus): void {
    this.status = status;
    this.changed();
  }

  private changed(): void {
    for (const listener of this.listeners) listener();
  }
}
