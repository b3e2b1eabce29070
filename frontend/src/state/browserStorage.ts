// The browser's storages, or null where there is none (tests) or it is refused (private
// mode): whatever keeps something in them must work without them, for the page's life only.

/** `globalThis[name]`, or null where it is missing or reading it throws. */
function reachable(name: "localStorage" | "sessionStorage"): Storage | null {
  try {
    return globalThis[name] ?? null;
  } catch {
    return null;
  }
}

/** localStorage: kept across visits. */
export const browserStorage = (): Storage | null => reachable("localStorage");

/** This tab's sessionStorage (what a page remembers while the person moves around in one
 * tab, e.g. the scene list's filter). */
export const tabStorage = (): Storage | null => reachable("sessionStorage");
