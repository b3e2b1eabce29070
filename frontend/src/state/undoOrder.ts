// One Undo and Redo for the page over several histories (the session's unsaved support and
// layout edits, the saved object actions): undo takes back whichever acted last, redo does again
// whichever was undone last, and only while nothing new was done since (a new action forgets
// what was undone, across histories as within one).

export interface Undoable {
  readonly undoStamp: number | null;
  readonly redoStamp: number | null;
  /** When the last new action (not a redo) was recorded. */
  readonly recordStamp: number | null;
  readonly undoLabel: string | null;
  readonly redoLabel: string | null;
  undo(): unknown;
  redo(): unknown;
}

const newest = (histories: readonly Undoable[], stamp: (h: Undoable) => number | null) => {
  let best: Undoable | null = null;
  for (const history of histories) {
    const value = stamp(history);
    if (value !== null && (best === null || value > (stamp(best) ?? -1))) best = history;
  }
  return best;
};

/** The history whose last action is the most recent (null: nothing to undo). */
export function latestUndo(histories: readonly Undoable[]): Undoable | null {
  return newest(histories, (h) => h.undoStamp);
}

/** The history whose undone action is the most recent, unless a new action came after it. */
export function latestRedo(histories: readonly Undoable[]): Undoable | null {
  const redo = newest(histories, (h) => h.redoStamp);
  const recorded = newest(histories, (h) => h.recordStamp)?.recordStamp ?? null;
  const stamp = redo?.redoStamp ?? null;
  return stamp !== null && (recorded === null || stamp > recorded) ? redo : null;
}
