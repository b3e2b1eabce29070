// Free class names resolved by their words, as the server does (holiscene_schema/class_words.py,
// which explains the steps): "office chair" is a chair, "book shelf" a bookshelf, "chair 2" a
// chair, "chiar" a chair. The word lists come from the contract (vocabulary.json), and
// shared_schema/vectors/class_names.json pins both sides to the same answers.
import { CLASS_WORDS } from "@holiscene/schema";

const GENERIC_HEADS = new Set<string>(CLASS_WORDS.generic_heads);
const PREPOSITIONS = new Set<string>(CLASS_WORDS.prepositions);
const IRREGULAR_PLURALS: Record<string, string> = CLASS_WORDS.irregular_plurals;

/** A key (words joined by "_") -> its class, or null. */
export type Lookup = (key: string) => string | null;

/** The name's words: lower case, a part in parentheses left out, every run of characters
 * other than a-z a break. */
export const classWords = (name: string): string[] =>
  name
    .toLowerCase()
    .replace(/\([^()]*\)/g, " ")
    .match(/[a-z]+/g) ?? [];

/** The word's singular by English spelling rules (chairs, couches, batteries, shelves). */
export function singular(word: string): string {
  const irregular = IRREGULAR_PLURALS[word];
  if (irregular !== undefined) return irregular;
  if (word.length <= 2 || /(ss|us|is)$/.test(word) || !word.endsWith("s")) return word;
  if (word.endsWith("ies") && word.length > 4) return `${word.slice(0, -3)}y`;
  if (word.endsWith("lves")) return `${word.slice(0, -3)}f`;
  if (/(ches|shes|xes|sses|zes)$/.test(word)) return word.slice(0, -2);
  return word.slice(0, -1);
}

/** The class of a name's words, or null: the words as one key, "X of Y" and "X on Y", the
 * head noun (a generic head after its modifiers), then a typo in the last word. */
export function resolveWords(
  words: string[],
  lookup: Lookup,
  knownWords: ReadonlySet<string>,
): string | null {
  if (words.length === 0) return null;
  const found = phrase(words, lookup) ?? byHead(words, lookup);
  if (found !== null) return found;
  const last = words[words.length - 1] ?? "";
  const fixed = new Set<string>();
  for (const form of new Set([last, singular(last)])) {
    for (const word of typoFixes(form, knownWords)) {
      const cls = lookup(word);
      if (cls !== null) fixed.add(cls);
    }
  }
  return fixed.size === 1 ? ([...fixed][0] ?? null) : null;
}

function phrase(words: string[], lookup: Lookup): string | null {
  for (const form of [words, words.map(singular)]) {
    for (const joiner of ["_", ""]) {
      const found = lookup(form.join(joiner));
      if (found !== null) return found;
    }
  }
  return null;
}

function byHead(words: string[], lookup: Lookup): string | null {
  const at = words.findIndex((w, i) => i > 0 && (w === "of" || PREPOSITIONS.has(w)));
  if (at !== -1) {
    const head = words.slice(0, at);
    const rest = words.slice(at + 1);
    if (words[at] === "of" && GENERIC_HEADS.has(singular(head[head.length - 1] ?? ""))) {
      return resolve(rest, lookup) ?? resolve(head, lookup);
    }
    return resolve(head, lookup);
  }
  if (GENERIC_HEADS.has(singular(words[words.length - 1] ?? "")) && words.length > 1) {
    const found = resolve(words.slice(0, -1), lookup);
    if (found !== null) return found;
  }
  for (let start = 1; start < words.length; start++) {
    const found = phrase(words.slice(start), lookup);
    if (found !== null) return found;
  }
  return null;
}

const resolve = (words: string[], lookup: Lookup): string | null =>
  words.length > 0 ? (phrase(words, lookup) ?? byHead(words, lookup)) : null;

/** The known words one typo away from `word`: neighbours swapped, a letter missing, or in a
 * long word one letter too many; sorted. */
export function typoFixes(word: string, knownWords: ReadonlySet<string>): string[] {
  if (word.length < CLASS_WORDS.shortest_typo) return [];
  const near = new Set<string>();
  for (let i = 0; i < word.length - 1; i++) {
    near.add(word.slice(0, i) + word.charAt(i + 1) + word.charAt(i) + word.slice(i + 2));
  }
  if (word.length >= CLASS_WORDS.longest_typo) {
    for (let i = 0; i < word.length; i++) near.add(word.slice(0, i) + word.slice(i + 1));
  }
  for (const known of knownWords) {
    if (known.length === word.length + 1 && oneOut(known, word)) near.add(known);
  }
  return [...near].filter((w) => knownWords.has(w) && w !== word).sort();
}

function oneOut(longer: string, shorter: string): boolean {
  for (let i = 0; i < longer.length; i++) {
    if (longer.slice(0, i) + longer.slice(i + 1) === shorter) return true;
  }
  return false;
}
