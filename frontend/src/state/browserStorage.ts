// The browser's localStorage, or null where there is none (tests) or it is refused (private
// mode): whatever keeps something in it must work without it, for the page's life only.
export function browserStorage(): Storage | null {
  try {
    return typeof localStorage === "undefined" ? null : localStorage;
  } catch {
    return null;
  }
}

/** This tab's sessionStorage (what a page remembers while the person moves around in one
 * tab, e.g. the scene list's filter), or null where it is blocked. */
export function tabStorage(): Storage | null {
  try {
    return typeof sessionStorage === "undefined" ? null : sessionStorage;
  } catch {
    return null;
  }
}
