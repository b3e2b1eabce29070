// The browser's localStorage, or null where there is none (tests) or it is refused (private
// mode): whatever keeps something in it must work without it, for the page's life only.
export function browserStorage(): Storage | null {
  try {
    return typeof localStorage === "undefined" ? null : localStorage;
  } catch {
    return null;
  }
}
