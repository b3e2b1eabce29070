// Work that follows an edit but that nobody is looking at when it lands (another panel's
// refresh, a request, the support model scoring again) waits until the browser has painted
// the edit: a new revision's listeners all run in one go, and whatever runs there holds the
// photo's redraw back.

/** A hidden page paints no frames: the work then runs after this long anyway. */
const HIDDEN_FALLBACK_MS = 200;

/** Run `task` once the next frame has been painted; returns a function that cancels it. */
export function afterPaint(task: () => void): () => void {
  let done = false;
  let timer: ReturnType<typeof setTimeout> | undefined;
  const run = () => {
    if (done) return;
    done = true;
    clearTimeout(timer);
    cancelAnimationFrame(frame);
    task();
  };
  // A frame callback runs before that frame's paint; a timer set there runs after it.
  const frame = requestAnimationFrame(() => {
    clearTimeout(timer);
    timer = setTimeout(run, 0);
  });
  timer = setTimeout(run, HIDDEN_FALLBACK_MS);
  return () => {
    done = true;
    clearTimeout(timer);
    cancelAnimationFrame(frame);
  };
}

/**
 * `task` made to run after the next paint, once however often it is asked for before then
 * (a revision adopted and its edits restaged ask twice). `cancel` drops a pending run.
 */
export function deferred(task: () => void): { (): void; cancel(): void } {
  let pending: (() => void) | null = null;
  const schedule = () => {
    pending ??= afterPaint(() => {
      pending = null;
      task();
    });
  };
  schedule.cancel = () => {
    pending?.();
    pending = null;
  };
  return schedule;
}
