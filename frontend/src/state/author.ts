// The annotator's name, sent with every edit and kept in localStorage.

const KEY = "holiscene.author";
export const DEFAULT_AUTHOR = "annotator";

export function getAuthor(): string {
  try {
    return localStorage.getItem(KEY)?.trim() || DEFAULT_AUTHOR;
  } catch {
    return DEFAULT_AUTHOR;
  }
}

export function setAuthor(name: string): void {
  try {
    localStorage.setItem(KEY, name.trim());
  } catch {
    // Storage may be unavailable (private mode); the name then lasts for this page only.
  }
}

/** Keep a text input and the stored author name in step. */
export function bindAuthorInput(input: HTMLInputElement): void {
  input.value = getAuthor();
  input.placeholder = DEFAULT_AUTHOR;
  input.addEventListener("change", () => {
    setAuthor(input.value);
    input.value = getAuthor();
  });
}
