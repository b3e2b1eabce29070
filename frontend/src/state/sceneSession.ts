// One scene being annotated: the loaded revision, the user's unsaved edits (supports and the
// room layout) with one undo and redo history, saving (and merging after a conflict), the
// drafts kept in localStorage, whether the scene may be edited now, the model's live
// suggestions, and what is hovered or selected. Views subscribe and redraw what a change
// concerns.
import type {
  RevisionInfo,
  SceneDocument,
  SceneObject,
  SceneWorkflow,
  SupportRelation,
} from "@holiscene/schema";
import { STRUCTURAL_SUPPORTERS } from "@holiscene/schema";
import { api } from "../api/client";
import { ApiError, ConflictError, errorText } from "../api/errors";
import { formatTime } from "../dom";
import { type Draft, DraftStore } from "./draftStore";
import { type HistoryChange, HistoryKeeper } from "./editHistory";
import { type EditLock, type EditPermission, editLock, lockText } from "./editLock";
import type { LayoutDraft, LayoutState } from "./layoutDraft";
import { trackSave } from "./savesInFlight";
import {
  describeEdit,
  type Edit,
  editProblem,
  isNoOp,
  type RestoreSupportEdit,
  type ShownSupport,
  type SupportType,
  sameRelation,
  shownSupports,
  wireEdit,
} from "./supportGraph";

export type SaveState =
  | { kind: "clean" }
  | { kind: "dirty" }
  | { kind: "saving" }
  | { kind: "saved"; revision: number }
  | {
      kind: "conflict";
      baseRevision: number;
      currentRevision: number | null;
      message: string;
      /** The revisions saved by others since `baseRevision` (empty if they could not be read). */
      theirs: RevisionInfo[];
    }
  | {
      kind: "error";
      message: string;
      /** A network or server failure, worth trying again (a refusal is not). */
      retry: boolean;
    };

/**
 * What changed: the document, the unsaved edits (and undo/redo), the save state, hover or
 * selection, the model's suggestions, the edits offered back from an earlier visit.
 */
export type Change =
  | "document"
  | "edits"
  | "save"
  | "hover"
  | "select"
  | "suggestions"
  | "recovery"
  | "message"
  | "lock";

/** The model's answer for an object whose supporter no person has set, when it differs. */
export interface SuggestedSupport {
  child: string;
  parent: string;
  type: SupportType;
  probability: number;
}

/** Computes the suggestions from the session's current state (see inference/liveSuggestions). */
export type Suggester = (session: SceneSession) => Map<string, SuggestedSupport>;

/** The arrow an object shows: its supporter, or the model's suggestion replacing a guess. */
export interface DisplayedSupport {
  child: string;
  parent: string;
  type: SupportType;
  suggested: boolean;
  /** The supporter as saved or edited (null: none). */
  support: ShownSupport | null;
}

/** One object's state, as undo and redo put it back: its supporter and rejected answers. */
interface ObjectState {
  edit: Edit;
  rejected: string[];
}

/** What one step of the history changed: an object's supporter, or the room layout. */
type HistoryState =
  | { part: "support"; state: ObjectState }
  | { part: "layout"; state: LayoutState };

/** Why autosave waits (see SceneSession.holdAutosave). */
export type AutosaveHold = "reload" | "undone discard";

/** Discard's action in the undo history. */
const DISCARD_LABEL = "discard unsaved changes";

/** The room layout's step of the history (objects are keyed by their id). */
const layoutChange = (before: LayoutState, after: LayoutState): HistoryChange<HistoryState> => ({
  key: "layout",
  before: { part: "layout", state: before },
  after: { part: "layout", state: after },
});

export const rejectionKey = (parent: string, type: string) => `${parent}|${type}`;

export class SceneSession extends HistoryKeeper<HistoryState> {
  doc: SceneDocument;
  saveState: SaveState = { kind: "clean" };
  hovered: string | null = null;
  selected: string | null = null;
  /** The object whose supporter the next click on another object picks (an arrow or a "?"
   * flag was clicked, or S pressed; editors/arrowEditing.ts), else null: clicks select. */
  picking: string | null = null;
  /** Why the last editing action did nothing, for the selection bar (null: nothing to say). */
  message: string | null = null;
  /** A message about the last reload or recovery (what happened to the unsaved edits). */
  notice: string | null = null;
  /** Unsaved edits an earlier visit left (in localStorage), until restored or discarded. */
  recovered: Draft | null;
  /** Why unsaved edits wait for Save instead of autosaving, until the person edits or saves:
   * after "reload" on a conflict (to review them first), or after Undo brought back what
   * Discard had dropped (an Undo meant for an earlier action stored them unseen). */
  holdAutosave: AutosaveHold | null = null;

  private readonly edits = new Map<string, Edit>();
  private readonly rejected = new Map<string, Set<string>>();
  private layout: LayoutDraft | null = null;
  /** The scene's place in the workflow, once known (it may lock the scene). */
  private workflow: SceneWorkflow | null = null;
  /** The server's latest word on editing (the scene's or the workflow's, whichever came last). */
  private permission: EditPermission | null = null;
  /** The server refused a save (409, not a stale revision) in this workflow state. */
  private refusal: { message: string; workflow: string } | null = null;
  /** "Run pipeline again" is running: the scene stays in view, read only, until its result. */
  private rerunning = false;
  private shownLock = "";
  private readonly listeners = new Set<(change: Change) => void>();
  /** Where unsaved work outlives the page (localStorage): drafts, a failed object action. */
  readonly drafts: DraftStore;
  private shownCache: Map<string, ShownSupport> | null = null;
  private suggester: Suggester | null = null;
  private doubter: (() => ReadonlySet<string>) | null = null;
  private suggestionCache: Map<string, SuggestedSupport> | null = null;

  constructor(doc: SceneDocument, options: { drafts?: DraftStore } = {}) {
    super();
    this.doc = doc;
    this.drafts = options.drafts ?? new DraftStore();
    this.recovered = this.drafts.takeForRecovery(doc.scene_id);
    this.permission = permissionOf(doc);
    this.shownLock = JSON.stringify(this.lock);
  }

  /**
   * The room layout being edited joins the session: its drags are steps of the one history,
   * its corners are saved with the support edits, and kept in the draft in localStorage.
   */
  attachLayout(draft: LayoutDraft): () => void {
    this.layout = draft;
    draft.onStep = (label, before, after) => this.record(label, [layoutChange(before, after)]);
    return () => {
      draft.onStep = null;
      // Moved corners not saved yet stay with the session: the page's last save, sent as it
      // is left (state/autosave.ts), runs after the layout editor is gone and must send them.
      if (this.layout === draft && !draft.dirty) this.layout = null;
    };
  }

  /** Whether the room layout has unsaved changes. */
  get layoutPending(): boolean {
    return this.layout?.dirty === true;
  }

  /** Unsaved changes: one per object, and one for the room layout. */
  get unsavedCount(): number {
    return this.edits.size + (this.layoutPending ? 1 : 0);
  }

  /** Whether there is something a save would send (a layout no room fits is not sent). */
  get savable(): boolean {
    return this.edits.size > 0 || this.layout?.edit() != null;
  }

  // -- whether the scene may be edited ---------------------------------------------------

  /**
   * Why the scene cannot be edited now (null: it can): the server says so (on the scene or
   * its workflow), or it is submitted or accepted, or the server refused the last save.
   */
  /** Read only for as long as the scene keeps its workflow state or its annotator (submitted,
   * accepted, someone else's): not a passing lock (a re-run, a refused save). The page then
   * leaves out controls that could only be greyed. */
  get viewOnly(): boolean {
    return editLock(this.workflow?.state, this.permission) !== null;
  }

  get lock(): EditLock | null {
    const lock = editLock(this.workflow?.state, this.permission);
    if (lock) return lock;
    if (this.rerunning) {
      return {
        title: "Pipeline running — read only",
        reason: "the pipeline runs again on this scene; its result replaces what is shown",
      };
    }
    return this.refusal && { title: "Read only", reason: this.refusal.message };
  }

  /** The page started (true) or gave up (false) a pipeline run of this scene. */
  setRerunning(running: boolean): void {
    this.rerunning = running;
    this.lockChanged();
  }

  get editable(): boolean {
    return this.lock === null;
  }

  /** The scene's workflow as last read (the workflow bar reads it). */
  setWorkflow(workflow: SceneWorkflow | null): void {
    this.workflow = workflow;
    // A refusal holds until the workflow moves on (submitted, sent back, taken, ...).
    if (this.refusal && this.refusal.workflow !== workflowKey(workflow)) this.refusal = null;
    this.permission = permissionOf(workflow) ?? this.permission;
    this.lockChanged();
  }

  get sceneId(): string {
    return this.doc.scene_id;
  }

  get objects(): SceneObject[] {
    return this.doc.scene.objects ?? [];
  }

  object(id: string): SceneObject | undefined {
    return this.objects.find((o) => o.id === id);
  }

  /** The selected object, if it is one (not a structure, nor gone). */
  get selectedObject(): SceneObject | undefined {
    return this.selected ? this.object(this.selected) : undefined;
  }

  /** Unsaved edits, in the order they were made (one per object). */
  get pending(): Edit[] {
    return [...this.edits.values()];
  }

  isPending(child: string): boolean {
    return this.edits.has(child);
  }

  savedSupport(child: string): SupportRelation | undefined {
    return (this.doc.scene.supports ?? []).find((s) => s.child === child);
  }

  /** Every object's supporter as shown: saved supports with unsaved edits applied. */
  shown(): Map<string, ShownSupport> {
    this.shownCache ??= shownSupports(this.doc.scene.supports ?? [], this.edits.values());
    return this.shownCache;
  }

  /** Answers rejected for this object ("parent|type", see rejectionKey). */
  rejectedAnswers(child: string): ReadonlySet<string> {
    return this.rejected.get(child) ?? new Set();
  }

  /** Whether a person set the object's supporter (saved or not): the model leaves it alone. */
  isResolved(child: string): boolean {
    return this.shown().get(child)?.source === "manual";
  }

  /** People's labels the support model is sure are something else (inference/labelDoubts.ts)
   * for the objects it last scored: child ids, none until it has scored them. The
   * suggestions panel sets where they come from; the submit question reads them. */
  doubtedLabels(): ReadonlySet<string> {
    return this.doubter?.() ?? new Set();
  }

  setDoubter(doubter: (() => ReadonlySet<string>) | null): void {
    this.doubter = doubter;
  }

  setSuggester(suggester: Suggester | null): void {
    this.suggester = suggester;
    this.suggestionCache = null;
    this.emit("suggestions");
  }

  /** The model's current suggestions (none until it has scored the scene). None while the
   * scene is read only: a reviewer, or someone locked out, sees what is stored. */
  suggestions(): Map<string, SuggestedSupport> {
    if (!this.editable) return new Map();
    this.suggestionCache ??= this.suggester?.(this) ?? new Map();
    return this.suggestionCache;
  }

  displayed(child: string): DisplayedSupport | null {
    const support = this.shown().get(child) ?? null;
    const suggestion = this.suggestions().get(child);
    if (suggestion) return { ...suggestion, suggested: true, support };
    return support
      ? { child, parent: support.parent, type: support.type, suggested: false, support }
      : null;
  }

  subscribe(listener: (change: Change) => void): () => void {
    this.listeners.add(listener);
    return () => this.listeners.delete(listener);
  }

  // -- editing, undo and redo -----------------------------------------------------------

  /**
   * One user action: stage the edits (an edit back to the saved state cancels) and remember
   * it for undo. `reject` adds answers the model must not suggest again for an object.
   */
  edit(
    label: string,
    edits: readonly Edit[],
    reject: readonly { child: string; parent: string; type: string }[] = [],
    layout: { before: LayoutState; after: LayoutState } | null = null,
  ): void {
    const lock = this.lock;
    if (lock !== null) {
      this.say(lockText(lock));
      return;
    }
    // A supporter set any way (a click, F/W/C, A, R, the list) spends an armed pick: the next
    // click selects again, as after a picked supporter.
    if (edits.length > 0 || reject.length > 0) this.setPicking(null);
    const before = new Map<string, ObjectState>();
    const touch = (child: string) => {
      if (!before.has(child)) before.set(child, this.stateOf(child));
    };
    for (const edit of edits) {
      touch(edit.child);
      this.stage(edit);
    }
    for (const r of reject) {
      touch(r.child);
      const keys = new Set(this.rejected.get(r.child));
      keys.add(rejectionKey(r.parent, r.type));
      this.rejected.set(r.child, keys);
    }
    const changes: HistoryChange<HistoryState>[] = [];
    for (const [key, state] of before) {
      const after = this.stateOf(key);
      if (!sameState(state, after)) {
        changes.push({
          key,
          before: { part: "support", state },
          after: { part: "support", state: after },
        });
      }
    }
    if (layout) changes.push(layoutChange(layout.before, layout.after));
    this.record(label, changes);
  }

  /** Remember an action for undo; the unsaved changes changed. */
  private record(label: string, changes: HistoryChange<HistoryState>[]): void {
    this.history.record({ label, changes });
    this.holdAutosave = null;
    this.notice = null; // what a merge or a recovery reported is old news now
    this.editsChanged();
  }

  /** Take back the last action; returns its label (null: nothing to undo, or read only). */
  undo(): string | null {
    if (!this.editable) return null;
    const entry = this.history.undo();
    if (!entry) return null;
    for (const change of entry.changes) this.applyState(change.key, change.before);
    this.holdAutosave = entry.label === DISCARD_LABEL ? "undone discard" : null;
    this.editsChanged();
    return entry.label;
  }

  /** Do the last undone action again; returns its label (null: nothing to redo, or read only). */
  redo(): string | null {
    if (!this.editable) return null;
    const entry = this.history.redo();
    if (!entry) return null;
    for (const change of entry.changes) this.applyState(change.key, change.after);
    this.holdAutosave = null;
    this.editsChanged();
    return entry.label;
  }

  /** Drop every unsaved change, the room layout's too (undoable). */
  discard(): void {
    this.notice = null;
    const layout = this.layout;
    let layoutChange: { before: LayoutState; after: LayoutState } | null = null;
    if (layout?.dirty && this.editable) {
      const before = layout.snapshot();
      layout.showStored(); // recorded below, with the supports, as one step
      layoutChange = { before, after: layout.snapshot() };
    }
    this.edit(
      DISCARD_LABEL,
      this.pending.map((e) => this.savedState(e.child)),
      [],
      layoutChange,
    );
  }

  /** The saved supporter of `child`, as an edit that would put it back. */
  private savedState(child: string): RestoreSupportEdit {
    return {
      kind: "restore_support",
      child,
      from_revision: this.doc.revision,
      restores: this.savedSupport(child) ?? null,
    };
  }

  private stateOf(child: string): ObjectState {
    return {
      edit: this.edits.get(child) ?? this.savedState(child),
      rejected: [...(this.rejected.get(child) ?? [])],
    };
  }

  private applyState(key: string, state: HistoryState): void {
    if (state.part === "layout") this.layout?.applyState(state.state);
    else this.applySupport(key, state.state);
  }

  private applySupport(child: string, state: ObjectState): void {
    this.stage(state.edit);
    if (state.rejected.length > 0) this.rejected.set(child, new Set(state.rejected));
    else this.rejected.delete(child);
  }

  private stage(edit: Edit): void {
    this.edits.delete(edit.child);
    if (!isNoOp(edit, this.doc.scene.supports ?? [])) this.edits.set(edit.child, edit);
  }

  // -- hover and selection --------------------------------------------------------------

  hover(id: string | null): void {
    if (this.hovered === id) return;
    this.hovered = id;
    this.emit("hover");
  }

  select(id: string | null): void {
    this.selected = id;
    if (this.picking !== id) this.picking = null; // another selection ends a pick
    this.emit("select");
  }

  /** Arm (an object id) or end (null) a supporter pick for the selected object. */
  setPicking(id: string | null): void {
    if (this.picking === id) return;
    this.picking = id;
    this.emit("select");
  }

  /** The person has read the notice (what a reload, merge or recovery reported). */
  dismissNotice(): void {
    this.notice = null;
    this.emit("message");
  }

  /** Tell the user why an action did nothing (null: clear). */
  say(message: string | null): void {
    this.message = message;
    this.emit("message");
  }

  // -- saving ---------------------------------------------------------------------------

  /**
   * Send the unsaved edits (and the room layout's), based on the loaded revision. They are
   * kept unless saved.
   */
  save(author: string): Promise<void> {
    const sending = this.send(author);
    trackSave(sending);
    return sending;
  }

  /** `mergeIfDisjoint`: on a conflict, rebase and send again once when no edit overlaps theirs. */
  private async send(author: string, mergeIfDisjoint = true): Promise<void> {
    if (this.saveState.kind === "saving" || !this.editable) return;
    const sent = this.pending;
    const layoutEdit = this.layout?.edit() ?? null;
    const layoutVersion = this.layout?.version ?? null;
    const [first, ...rest] = [...sent.map(wireEdit), ...(layoutEdit ? [layoutEdit] : [])];
    if (!first) return;
    const baseRevision = this.doc.revision;
    this.holdAutosave = null;
    this.setSaveState({ kind: "saving" });
    try {
      const doc = await api.postEdits(this.sceneId, {
        base_revision: baseRevision,
        author,
        edits: [first, ...rest],
      });
      for (const edit of sent) {
        if (this.edits.get(edit.child) === edit) this.edits.delete(edit.child);
      }
      this.setDocument(doc, layoutEdit ? layoutVersion : null);
      // Edits made while saving stay; those the new revision already has are dropped.
      for (const edit of this.pending) this.stage(edit);
      this.saveState = { kind: "saved", revision: doc.revision };
      this.editsChanged();
    } catch (error) {
      // A 409 without a current revision is the workflow's refusal (the scene is someone
      // else's, or submitted), not a newer revision: nothing to merge. The edits are kept
      // (here and in localStorage) and the editor is read only until the workflow changes.
      if (error instanceof ConflictError && error.currentRevision !== null) {
        // Someone saved other objects meanwhile: nothing to choose, so the edits go on top
        // of theirs by themselves, and the notice says so.
        const latest = mergeIfDisjoint ? await api.getScene(this.sceneId).catch(() => null) : null;
        if (latest && !this.clashesWith(latest)) {
          await this.reloadLatest({ latest, merged: true });
          if (this.saveState.kind !== "error") await this.send(author, false);
          return;
        }
        const theirs = await api
          .listRevisions(this.sceneId)
          .then((all) => all.filter((r) => r.number > baseRevision))
          .catch(() => []);
        this.setSaveState({
          kind: "conflict",
          baseRevision,
          currentRevision: error.currentRevision,
          message: error.message,
          theirs,
        });
      } else {
        const refused = error instanceof ApiError && error.status < 500;
        this.setSaveState({ kind: "error", message: errorText(error), retry: !refused });
        if (error instanceof ConflictError) {
          this.refusal = { message: error.message, workflow: workflowKey(this.workflow) };
          this.lockChanged();
        }
      }
    }
  }

  /**
   * Whether the unsaved edits cannot go on top of `latest` unasked: both sides changed an
   * object's support (or both moved the room's corners), or `latest` can no longer take one.
   */
  private clashesWith(latest: SceneDocument): boolean {
    const objects = latest.scene.objects ?? [];
    const clash = (edit: Edit) =>
      editProblem(edit, objects) !== null ||
      (!isNoOp(edit, latest.scene.supports ?? []) && supportChanged(this.doc, latest, edit.child));
    return this.pending.some(clash) || (this.layoutPending && layoutMoved(this.doc, latest));
  }

  /**
   * Load the latest revision and put the unsaved edits back on top of it, dropping only the
   * ones that no longer apply or that the latest revision already has, and saying which
   * objects both sides changed. `hold`: do not autosave until the user acts (review first).
   * `latest`: the revision, fetched already; `merged`: it is loaded because the edits touch
   * other objects than the revisions since, and they are being saved on top.
   */
  async reloadLatest(
    options: { hold?: boolean; latest?: SceneDocument; merged?: boolean } = {},
  ): Promise<void> {
    const previous = this.doc;
    try {
      const [doc, revisions] = await Promise.all([
        options.latest ?? api.getScene(this.sceneId),
        api.listRevisions(this.sceneId).catch(() => []),
      ]);
      const lines: string[] = [];
      const newer = revisions.filter((r) => r.number > previous.revision);
      lines.push(
        newer.length > 0
          ? `Loaded revision ${doc.revision}. Changed since revision ${previous.revision}: ` +
              newer.map((r) => `#${r.number} by ${r.author} (${r.summary})`).join("; ") +
              "."
          : `Loaded revision ${doc.revision}.`,
      );
      const after = (child: string) => supportOf(doc, child);
      lines.push(...this.dropUnsavable(doc));
      for (const edit of this.pending) {
        if (isNoOp(edit, doc.scene.supports ?? [])) {
          lines.push(`Your edit "${describeEdit(edit)}" is already in revision ${doc.revision}.`);
          this.edits.delete(edit.child);
        } else if (supportChanged(previous, doc, edit.child)) {
          const theirs = after(edit.child);
          lines.push(
            `Both of you changed ${edit.child}: yours is kept on top (theirs: ` +
              (theirs ? `on ${theirs.parent}, ${theirs.type}` : "no supporter") +
              ").",
          );
        }
      }
      if (this.layoutPending && layoutMoved(previous, doc)) {
        lines.push("Both of you changed the room layout: your corners are kept on top.");
      }
      const unsaved = this.unsavedCount;
      if (options.merged && unsaved > 0) {
        lines.push(
          `Your ${plural(unsaved, "change")} ${unsaved === 1 ? "touches" : "touch"} other objects: ` +
            `${unsaved === 1 ? "it is" : "they are"} saved on top.`,
        );
      } else if (unsaved > 0) {
        lines.push(
          `Your ${plural(unsaved, "unsaved change")} ${unsaved === 1 ? "is" : "are"} applied on top` +
            (options.hold ? "; review and save." : "."),
        );
      }
      // Nothing new and nothing of theirs to tell (a reload after a workflow step): no notice.
      this.notice = newer.length === 0 && lines.length === 1 ? null : lines.join(" ");
      this.holdAutosave = options.hold === true && unsaved > 0 ? "reload" : null;
      this.saveState = { kind: "clean" }; // the conflict is resolved; editsChanged() says what is left
      this.setDocument(doc);
      this.editsChanged();
    } catch (error) {
      this.setSaveState({
        kind: "error",
        message: `Reload failed: ${errorText(error)}`,
        retry: false,
      });
    }
  }

  /**
   * A revision the server made from edits sent outside the save (objects accepted from the
   * detector) becomes the loaded one; the unsaved edits stay on top, as after a save.
   */
  adopt(doc: SceneDocument): void {
    if (doc.scene_id !== this.sceneId) return;
    this.setDocument(doc);
    const pending = this.pending;
    const dropped = this.dropUnsavable(doc);
    for (const edit of this.pending) this.stage(edit);
    if (dropped.length > 0) this.notice = dropped.join(" ");
    // Without unsaved edits the supports shown and suggested are the new document's, worked
    // out already by the views that drew it: kept, not decoded again.
    this.editsChanged(pending.length === 0);
  }

  /**
   * Drop the unsaved edits `doc` can no longer take (a supporter of, or on, an object it does
   * not hold): the server would refuse the other unsaved edits with them. What was dropped.
   */
  private dropUnsavable(doc: SceneDocument): string[] {
    return this.pending.flatMap((edit) => {
      const problem = editProblem(edit, doc.scene.objects ?? []);
      if (!problem) return [];
      this.edits.delete(edit.child);
      return [`Dropped your unsaved edit "${describeEdit(edit)}": ${problem}.`];
    });
  }

  /** After a conflict: the latest revision with the unsaved edits on top, saved at once. */
  async merge(author: string): Promise<void> {
    await this.reloadLatest();
    if (this.saveState.kind !== "error") await this.save(author);
  }

  // -- edits left by an earlier visit ---------------------------------------------------

  /** Put the edits an earlier visit left unsaved back (one undoable action). */
  restoreRecovered(): void {
    const draft = this.recovered;
    if (!draft || !this.editable) return;
    const lines: string[] = [];
    const usable = draft.edits.filter((edit) => {
      const problem = editProblem(edit, this.objects);
      if (problem) lines.push(`Dropped "${describeEdit(edit)}": ${problem}.`);
      else if (isNoOp(edit, this.doc.scene.supports ?? []))
        lines.push(`"${describeEdit(edit)}" is already saved.`);
      return !problem && !isNoOp(edit, this.doc.scene.supports ?? []);
    });
    let layoutChange: { before: LayoutState; after: LayoutState } | null = null;
    if (draft.layout && this.layout) {
      const before = this.layout.snapshot();
      this.layout.applyState(draft.layout);
      layoutChange = { before, after: this.layout.snapshot() };
      if (!this.layout.dirty) lines.push("The room layout is already saved.");
    }
    const count = usable.length + (layoutChange && this.layout?.dirty ? 1 : 0);
    const when = formatTime(draft.savedAt); // as the banner offering them said
    lines.unshift(`Restored ${plural(count, "unsaved change")} from ${when}.`);
    this.recovered = null;
    this.drafts.clearRecovered(this.sceneId);
    this.edit("restore unsaved changes", usable, [], layoutChange);
    this.notice = lines.join(" ");
    this.emit("recovery");
  }

  dismissRecovered(): void {
    this.recovered = null;
    this.drafts.clearRecovered(this.sceneId);
    this.emit("recovery");
  }

  // -- internals ------------------------------------------------------------------------

  /** `layoutVersion`: the layout corners this revision stored (a save sent them). */
  private setDocument(doc: SceneDocument, layoutVersion: number | null = null): void {
    this.doc = doc;
    this.permission = permissionOf(doc) ?? this.permission;
    this.shownCache = null;
    this.suggestionCache = null;
    this.layout?.setDocument(doc, layoutVersion);
    this.emit("document");
    this.lockChanged();
    // A removed object stays neither hovered (which dims every other) nor selected.
    const present = (id: string | null) =>
      id === null ||
      (STRUCTURAL_SUPPORTERS as readonly string[]).includes(id) ||
      this.object(id) !== undefined;
    if (!present(this.hovered)) this.hover(null);
    if (!present(this.selected)) this.select(null);
  }

  /** `keepCaches`: the supports shown and suggested did not change (nothing was restaged). */
  private editsChanged(keepCaches = false): void {
    if (!keepCaches) {
      this.shownCache = null;
      this.suggestionCache = null;
    }
    this.drafts.save({
      sceneId: this.sceneId,
      baseRevision: this.doc.revision,
      edits: this.pending,
      layout: this.layoutPending ? (this.layout?.snapshot() ?? null) : null,
      savedAt: new Date().toISOString(),
    });
    this.emit("edits");
    const state = this.saveState.kind;
    const unsaved = this.unsavedCount;
    if (state === "saving" || (state === "conflict" && unsaved > 0)) return;
    if (state === "saved" && unsaved === 0) {
      this.emit("save");
      return;
    }
    this.setSaveState(unsaved > 0 ? { kind: "dirty" } : { kind: "clean" });
  }

  /** Say when the lock changed; once the scene is editable again, its kept edits can be saved. */
  private lockChanged(): void {
    const lock = this.lock;
    const key = JSON.stringify(lock);
    if (key === this.shownLock) return;
    const wasLocked = this.shownLock !== "null";
    this.shownLock = key;
    if (lock !== null) this.layout?.setEditing(false);
    this.emit("lock");
    this.suggestionCache = null;
    this.emit("suggestions"); // shown only while editable
    if (wasLocked && lock === null && this.saveState.kind === "error") {
      this.setSaveState(this.unsavedCount > 0 ? { kind: "dirty" } : { kind: "clean" });
    }
  }

  private setSaveState(state: SaveState): void {
    this.saveState = state;
    this.emit("save");
  }

  private emit(change: Change): void {
    for (const listener of this.listeners) listener(change);
  }
}

function sameState(a: ObjectState, b: ObjectState): boolean {
  const key = (s: ObjectState) => JSON.stringify([s.edit, [...s.rejected].sort()]);
  return key(a) === key(b);
}

/** The server's word on editing in a scene or workflow answer (null: an older server's). */
function permissionOf(answer: EditPermission | null): EditPermission | null {
  return typeof answer?.editable === "boolean" ? answer : null;
}

/** The workflow as far as a refusal depends on it: its state and who annotates it. */
const workflowKey = (workflow: SceneWorkflow | null) =>
  workflow ? `${workflow.state}|${workflow.assignee ?? ""}|${workflow.revision}` : "";

export function plural(count: number, noun: string): string {
  if (count === 1) return `${count} ${noun}`;
  return `${count} ${noun}${/(s|x|ch|sh)$/.test(noun) ? "es" : "s"}`;
}

const supportOf = (doc: SceneDocument, child: string) =>
  doc.scene.supports?.find((s) => s.child === child);

/** Whether `child`'s support differs between two revisions. */
const supportChanged = (before: SceneDocument, after: SceneDocument, child: string) =>
  !sameRelation(supportOf(before, child), supportOf(after, child));

/** Whether the room's corners differ between two revisions. */
function layoutMoved(before: SceneDocument, after: SceneDocument): boolean {
  return (
    JSON.stringify(before.scene.layout?.corners_2d) !==
    JSON.stringify(after.scene.layout?.corners_2d)
  );
}
