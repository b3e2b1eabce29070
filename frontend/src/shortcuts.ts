// Keyboard shortcuts: one registry for the whole app, so every key is listed in the help
// overlay (?) by the same code that runs it. Views register their keys when they mount and
// remove them when they go; of two registrations of one key, the newer enabled one wins (an
// open dialog's Escape before the page's).

export interface ShortcutSpec {
  /** "A", "Shift+A", "Ctrl+Shift+Z", "?", "Delete", "Escape"; several for aliases. */
  keys: string | readonly string[];
  description: string;
  /** The group it is listed under: "General", "Support editing", ... */
  scope: string;
  run: (event: KeyboardEvent) => void;
  /** When it returns false the key is left alone (e.g. nothing selected). */
  enabled?: () => boolean;
  /** Whether the help lists it at all: false for a key that is never this person's (a
   *  reviewer's key shown to an annotator). */
  listed?: () => boolean;
  /** Runs instead of `run` when the key is pressed while off and nothing else takes it: says
   *  why nothing happens (an editing tool's key on a read-only scene). */
  whenOff?: (event: KeyboardEvent) => void;
}

export interface Shortcut {
  keys: readonly string[];
  description: string;
  scope: string;
  /** Whether the key does something now (e.g. editing keys are off on a read-only scene). */
  enabled: boolean;
}

interface Entry extends Omit<Shortcut, "enabled"> {
  spec: ShortcutSpec;
}

const entries: Entry[] = [];
let listening = false;

const MODIFIERS = ["Ctrl", "Alt", "Shift"] as const;
const ALIASES: Record<string, string> = {
  Esc: "Escape",
  Del: "Delete",
  " ": "Space",
  Spacebar: "Space",
  Cmd: "Ctrl",
  Meta: "Ctrl",
  Control: "Ctrl",
};

/** A key's name as the registry writes it: modifiers in a fixed order, letters upper case. */
export function normalizeKeys(keys: string): string {
  // "+" alone or at the end is the plus key itself, not a separator.
  const parts = keys === "+" ? ["+"] : keys.split(/\+(?!$)/);
  const base = parts.pop() ?? "";
  const capital = (p: string) => p.charAt(0).toUpperCase() + p.slice(1).toLowerCase();
  const mods = new Set(parts.map((p) => ALIASES[capital(p)] ?? capital(p)));
  const key = ALIASES[base] ?? (base.length === 1 ? base.toUpperCase() : base);
  return [...MODIFIERS.filter((m) => mods.has(m)), key].join("+");
}

/** The registry's name of a key press; Shift counts only where it does not make the symbol. */
export function eventKeys(
  event: Pick<KeyboardEvent, "key" | "ctrlKey" | "metaKey" | "altKey" | "shiftKey">,
): string {
  const raw = ALIASES[event.key] ?? event.key;
  const printable = raw.length === 1;
  const letter = /^[a-z]$/i.test(raw);
  const mods: string[] = [];
  if (event.ctrlKey || event.metaKey) mods.push("Ctrl");
  if (event.altKey) mods.push("Alt");
  // "?" is Shift+/ on most layouts: the symbol already says it.
  if (event.shiftKey && (letter || !printable)) mods.push("Shift");
  return [...mods, printable ? raw.toUpperCase() : raw].join("+");
}

/** Typing in a text field, or choosing in a list, keeps its keys (modified keys aside). */
function typingTarget(event: KeyboardEvent): boolean {
  const target = event.target;
  // No DOM (unit tests): nothing is being typed in.
  if (typeof HTMLElement === "undefined" || !(target instanceof HTMLElement)) return false;
  if (target.isContentEditable || target instanceof HTMLTextAreaElement) return true;
  if (target instanceof HTMLInputElement) {
    return !["checkbox", "radio", "button", "submit", "reset", "range", "color"].includes(
      target.type,
    );
  }
  if (target instanceof HTMLSelectElement) {
    // A list has no use for Escape or Shift+Enter (submit, accept): they stay the page's, so
    // submitting right after choosing a supporter in its list works.
    const pageKey = event.key === "Escape" || (event.key === "Enter" && event.shiftKey);
    return !(event.ctrlKey || event.metaKey || event.altKey) && !pageKey;
  }
  return false;
}

/** What a key press on the page does (the window's keydown listener). */
export function handleShortcutKey(event: KeyboardEvent): void {
  if (event.defaultPrevented || event.isComposing || typingTarget(event)) return;
  const name = eventKeys(event);
  let off: ShortcutSpec | null = null;
  for (let i = entries.length - 1; i >= 0; i--) {
    const entry = entries[i];
    if (!entry?.keys.includes(name)) continue;
    if (entry.spec.enabled && !entry.spec.enabled()) {
      off ??= entry.spec.whenOff ? entry.spec : null;
      continue;
    }
    event.preventDefault();
    entry.spec.run(event);
    return;
  }
  if (off?.whenOff) {
    event.preventDefault();
    off.whenOff(event);
  }
}

/** Add a shortcut; returns the function that removes it. */
export function registerShortcut(spec: ShortcutSpec): () => void {
  const keys = (typeof spec.keys === "string" ? [spec.keys] : [...spec.keys]).map(normalizeKeys);
  const entry: Entry = { keys, description: spec.description, scope: spec.scope, spec };
  entries.push(entry);
  if (!listening && typeof window !== "undefined") {
    window.addEventListener("keydown", handleShortcutKey);
    listening = true;
  }
  return () => {
    const index = entries.indexOf(entry);
    if (index >= 0) entries.splice(index, 1);
  };
}

/**
 * The shortcuts for the help, in the order they were registered, and whether each is on now.
 * Of two registrations of the same keys in one scope (Shift+Enter: submit, or accept), only
 * the one a press would run is listed; when neither is on, both are (greyed).
 */
export function listShortcuts(): Shortcut[] {
  const listed = entries
    .filter(({ spec }) => spec.listed?.() ?? true)
    .map(({ keys, description, scope, spec }) => ({
      keys,
      description,
      scope,
      enabled: spec.enabled?.() ?? true,
    }));
  const sameKeys = (a: Shortcut, b: Shortcut) =>
    a.scope === b.scope && a.keys.join(" ") === b.keys.join(" ");
  return listed.filter((shortcut) => {
    const running = listed.findLast((other) => sameKeys(shortcut, other) && other.enabled);
    return running === undefined || running === shortcut;
  });
}
