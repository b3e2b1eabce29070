// Undo and redo: a list of actions, each the states of the things it changed before and after
// (one object's supporter, ...). The session applies the states; this only keeps the order.
// Every move of an action (done, undone, redone) takes a stamp from one counter shared by all
// histories, so the page can tell which of several histories acted last (state/undoOrder.ts).

export interface HistoryChange<S> {
  key: string;
  before: S;
  after: S;
}

export interface HistoryEntry<S> {
  label: string;
  changes: HistoryChange<S>[];
}

const LIMIT = 500;

let lastStamp = 0;
const nextStamp = () => ++lastStamp;

type Stamped<S> = HistoryEntry<S> & { stamp: number };

export class EditHistory<S> {
  private readonly done: Stamped<S>[] = [];
  private readonly undone: Stamped<S>[] = [];
  private recorded: number | null = null;

  /** Add an action; a new action forgets what was undone. */
  record(entry: HistoryEntry<S>): void {
    if (entry.changes.length === 0) return;
    this.recorded = nextStamp();
    this.done.push({ ...entry, stamp: this.recorded });
    if (this.done.length > LIMIT) this.done.shift();
    this.undone.length = 0;
  }

  /** The action to take back (its `before` states are to be applied), or null. */
  undo(): HistoryEntry<S> | null {
    const entry = this.done.pop() ?? null;
    if (entry) this.undone.push({ ...entry, stamp: nextStamp() });
    return entry;
  }

  /** The action to do again (its `after` states are to be applied), or null. */
  redo(): HistoryEntry<S> | null {
    const entry = this.undone.pop() ?? null;
    if (entry) this.done.push({ ...entry, stamp: nextStamp() });
    return entry;
  }

  get undoLabel(): string | null {
    return this.done.at(-1)?.label ?? null;
  }

  get redoLabel(): string | null {
    return this.undone.at(-1)?.label ?? null;
  }

  /** When the action undo would take back was done (or redone); null: nothing to undo. */
  get undoStamp(): number | null {
    return this.done.at(-1)?.stamp ?? null;
  }

  /** When the last new action was recorded (not redone); null: none yet. */
  get recordStamp(): number | null {
    return this.recorded;
  }

  /** When the action redo would do again was undone; null: nothing to redo. */
  get redoStamp(): number | null {
    return this.undone.at(-1)?.stamp ?? null;
  }
}

/**
 * Something whose actions one history keeps (the session's unsaved edits, the object editor's
 * saved actions): the page's Undo and Redo read its labels and stamps (state/undoOrder.ts).
 */
export abstract class HistoryKeeper<S> {
  protected readonly history = new EditHistory<S>();

  get undoLabel(): string | null {
    return this.history.undoLabel;
  }

  get redoLabel(): string | null {
    return this.history.redoLabel;
  }

  get undoStamp(): number | null {
    return this.history.undoStamp;
  }

  get redoStamp(): number | null {
    return this.history.redoStamp;
  }

  get recordStamp(): number | null {
    return this.history.recordStamp;
  }
}
