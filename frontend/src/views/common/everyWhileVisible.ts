// Pages that follow what others do (the workflow bar, the dashboard) look again every few
// seconds, but only while their tab is visible: a tab in the background asks nothing.

/** Call `check` every `ms` milliseconds while the tab is visible; returns how to stop. */
export function everyWhileVisible(ms: number, check: () => void): () => void {
  const timer = setInterval(() => {
    if (document.visibilityState === "visible") check();
  }, ms);
  return () => clearInterval(timer);
}
