// Undo and redo: a list of actions, each the states of the things it changed before and after
// (one object's supporter, ...). The session applies the states; this only keeps the order.

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

export class EditHistory<S> {
  private readonly done: HistoryEntry<S>[] = [];
  private readonly undone: HistoryEntry<S>[] = [];

  /** Add an action; a new action forgets what was undone. */
  record(entry: HistoryEntry<S>): void {
    if (entry.changes.length === 0) return;
    this.done.push(entry);
    if (this.done.length > LIMIT) this.done.shift();
    this.undone.length = 0;
  }

  /** The action to take back (its `before` states are to be applied), or null. */
  undo(): HistoryEntry<S> | null {
    const entry = this.done.pop() ?? null;
    if (entry) this.undone.push(entry);
    return entry;
  }

  /** The action to do again (its `after` states are to be applied), or null. */
  redo(): HistoryEntry<S> | null {
    const entry = this.undone.pop() ?? null;
    if (entry) this.done.push(entry);
    return entry;
  }

  get undoLabel(): string | null {
    return this.done.at(-1)?.label ?? null;
  }

  get redoLabel(): string | null {
    return this.undone.at(-1)?.label ?? null;
  }
}
