// The annotator's name, sent with every edit and kept in localStorage. In single-user mode it
// is what tells people apart (the server records it); until one is typed, the signed-in
// account's name stands in, so the supports and the workflow name the same person.

const KEY = "holiscene.author";
export const DEFAULT_AUTHOR = "annotator";
let fallback = DEFAULT_AUTHOR;
let boundInput: HTMLInputElement | null = null;

export function getAuthor(): string {
  try {
    return localStorage.getItem(KEY)?.trim() || fallback;
  } catch {
    return fallback;
  }
}

export function setAuthor(name: string): void {
  try {
    localStorage.setItem(KEY, name.trim());
  } catch {
    // Storage may be unavailable (private mode); the name then lasts for this page only.
  }
}

/** The name used while none is typed: the signed-in account's (null: none signed in). */
export function setAuthorFallback(name: string | null): void {
  fallback = name?.trim() || DEFAULT_AUTHOR;
  if (boundInput) showIn(boundInput);
}

function showIn(input: HTMLInputElement): void {
  input.value = getAuthor();
  input.placeholder = fallback;
}

/** Keep a text input and the stored author name in step. */
export function bindAuthorInput(input: HTMLInputElement): void {
  boundInput = input;
  showIn(input);
  input.addEventListener("change", () => {
    setAuthor(input.value);
    input.value = getAuthor();
  });
}
