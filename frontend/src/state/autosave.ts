// Autosave: unsaved edits go to the server after a short idle time (each new edit restarts
// the wait), again when edits were made during a save, and once more when the page leaves.
// A conflict stops it until the user merges or reloads; a save that failed on the way is
// retried, one the server refused (e.g. not allowed) waits for the user's next edit, or for
// the scene to be editable again, or for the person to log in again (a save refused because
// the session ended is sent once they have). Nothing is sent while the scene is read only.
import { getCurrentUser, onCurrentUserChange } from "./currentUser";
import { saveDone, trackSave } from "./savesInFlight";
import type { SceneSession } from "./sceneSession";

export interface AutosaveOptions {
  author: () => string;
  /** Idle time after the last edit (ms). */
  delayMs?: number;
  /** Wait before retrying a save that failed (ms). */
  retryMs?: number;
  /**
   * True while something else is saving to the scene (an object action): a save based on the
   * revision it is replacing would only conflict, so it waits (checked every OTHER_SAVE_MS).
   */
  otherSaving?: () => boolean;
}

export const AUTOSAVE_DELAY_MS = 1500;
const OTHER_SAVE_MS = 250;

/** The idle time before saving: the default, or this browser's setting (ms, 0 = off). */
export function autosaveDelay(): number {
  try {
    const stored = localStorage.getItem("holiscene.autosaveDelayMs");
    const ms = stored === null ? Number.NaN : Number(stored);
    return Number.isFinite(ms) && ms >= 0 ? ms : AUTOSAVE_DELAY_MS;
  } catch {
    return AUTOSAVE_DELAY_MS;
  }
}

export function startAutosave(session: SceneSession, options: AutosaveOptions): () => void {
  const delay = options.delayMs ?? autosaveDelay();
  const retry = options.retryMs ?? 5000;
  let timer: ReturnType<typeof setTimeout> | null = null;

  const cancel = () => {
    if (timer !== null) clearTimeout(timer);
    timer = null;
  };
  // Only under the session of the person whose edits these are: someone else logging in
  // over the page (or after a log-out) must not save them under their name.
  const ownerSignedIn = () =>
    session.drafts.owner === null || getCurrentUser()?.name === session.drafts.owner;
  const canSave = () => {
    const state = session.saveState.kind;
    return (
      ownerSignedIn() &&
      session.savable &&
      session.editable &&
      !session.holdAutosave &&
      state !== "saving" &&
      state !== "conflict"
    );
  };
  const schedule = (ms: number) => {
    cancel();
    if (!canSave() || delay === 0) return;
    timer = setTimeout(() => {
      timer = null;
      if (options.otherSaving?.()) schedule(OTHER_SAVE_MS);
      else if (canSave()) void session.save(options.author());
    }, ms);
  };

  const unsubscribe = session.subscribe((change) => {
    const state = session.saveState;
    if (change === "edits") schedule(delay);
    else if (change !== "save") return;
    else if (state.kind === "error") {
      if (state.retry) schedule(retry);
    } else if (state.kind === "dirty" || state.kind === "saved") schedule(delay);
  });
  const stopHearingLogins = onCurrentUserChange((user) => {
    if (user) schedule(delay);
  });
  schedule(delay);
  return () => {
    unsubscribe();
    stopHearingLogins();
    cancel();
    // Leaving the scene: send what is left now or, when a save is on its way, as soon as it
    // has landed (edits made during it would otherwise wait for a page that is gone); the
    // draft in localStorage stays until they land.
    const sendRest = () => {
      if (canSave()) void session.save(options.author());
    };
    if (session.saveState.kind === "saving") trackSave(saveDone(session).then(sendRest));
    else sendRest();
  };
}
