// Closing the tab or reloading while changes are unsaved (autosave waits for a pause) or on
// their way: the browser asks first. The draft in localStorage would offer them back in this
// browser only; on another machine they would be gone.
import type { SceneSession } from "../../state/sceneSession";

/** Whether leaving now would leave changes behind. */
export const hasWorkInFlight = (session: SceneSession): boolean =>
  session.unsavedCount > 0 || session.saveState.kind === "saving";

/** Ask before the page unloads while `session` has unsaved work; returns the remover. */
export function warnBeforeLeaving(session: SceneSession): () => void {
  const onBeforeUnload = (event: BeforeUnloadEvent) => {
    if (!hasWorkInFlight(session)) return;
    event.preventDefault();
    event.returnValue = ""; // older browsers ask only when this is set
  };
  window.addEventListener("beforeunload", onBeforeUnload);
  return () => window.removeEventListener("beforeunload", onBeforeUnload);
}
