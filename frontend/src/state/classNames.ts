// Class names compared and stored the server's way (holiscene_schema/classes.py: class_key,
// normalise_class_name); shared_schema/vectors/class_names.json holds both sides together.
import { CLASS_ALIASES, NYU40_CLASSES } from "@holiscene/schema";
import { classWords, resolveWords } from "./classWords";

const ALIASES: Record<string, string> = CLASS_ALIASES;
const CLASSES = new Set<string>(NYU40_CLASSES);
const KEYS: [string, string][] = [...NYU40_CLASSES.map((c): [string, string] => [c, c])];
KEYS.push(...Object.entries(ALIASES));
// Every key with its "_" left out too, for names typed joined ("coffeetable").
const JOINED = new Map(KEYS.map(([key, cls]) => [key.replaceAll("_", ""), cls]));
// The one-word keys: what a typo in a name may be fixed to.
const KNOWN_WORDS = new Set(KEYS.map(([key]) => key).filter((key) => !key.includes("_")));

const knownKey = (key: string): string | null =>
  CLASSES.has(key) ? key : (ALIASES[key] ?? JOINED.get(key) ?? null);

/** A name as the lookups compare it: trimmed, lower case, words joined by one "_". */
export const classKey = (text: string): string =>
  text
    .toLowerCase()
    .split(/[\s_-]+/)
    .filter((word) => word.length > 0)
    .join("_");

/** The name shown for a class: "night stand" for `night_stand`. */
export const classText = (cls: string): string => cls.replaceAll("_", " ");

/** An object's class as the page shows it: a name it was picked or imported under that maps
 * to the class (stool: chair) in brackets, "chair (stool)". */
export const objectClassText = (object: { class: string; source_class?: string | null }) =>
  object.source_class && object.source_class !== object.class
    ? `${classText(object.class)} (${object.source_class})`
    : classText(object.class);

/** The NYU-40 class a name is stored as: a class, an alias, a plural of either ("chairs",
 * "couches"), or a free name resolved by its words ("office chair", "chiar"); null when the
 * server would refuse it. */
export function storedClass(name: string): string | null {
  const key = classKey(name);
  const candidates = [key];
  if (key.endsWith("s")) candidates.push(key.slice(0, -1));
  if (key.endsWith("es")) candidates.push(key.slice(0, -2));
  for (const candidate of candidates) {
    if (CLASSES.has(candidate)) return candidate;
    if (candidate in ALIASES) return ALIASES[candidate] ?? null;
  }
  return resolveWords(classWords(name), knownKey, KNOWN_WORDS);
}
