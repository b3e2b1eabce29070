// Saves still on their way to the server. Logging out waits for them (for a while) before it
// ends the session: the last edits of a page are sent when it is left, and must land under the
// session of the person who made them (what does not land stays in their drafts).
import type { SceneSession } from "./sceneSession";

const inFlight = new Set<Promise<unknown>>();

/** Count `save` as on its way until it settles. */
export function trackSave(save: Promise<unknown>): void {
  inFlight.add(save);
  const done = () => inFlight.delete(save);
  save.then(done, done);
}

/** Resolves when every save on its way has settled, or after `timeoutMs`. */
export async function savesLanded(timeoutMs = 10_000): Promise<void> {
  if (inFlight.size === 0) return;
  let timer: ReturnType<typeof setTimeout> | undefined;
  const timeout = new Promise<void>((resolve) => {
    timer = setTimeout(resolve, timeoutMs);
  });
  await Promise.race([Promise.allSettled([...inFlight]), timeout]);
  clearTimeout(timer);
}

/** Until the session is not saving (an object edit must not race a support save, nor the
 * last save of a page left the one on its way). */
export function saveDone(session: Pick<SceneSession, "saveState" | "subscribe">): Promise<void> {
  if (session.saveState.kind !== "saving") return Promise.resolve();
  return new Promise((resolve) => {
    const stop = session.subscribe((change) => {
      if (change === "save" && session.saveState.kind !== "saving") {
        stop();
        resolve();
      }
    });
  });
}
