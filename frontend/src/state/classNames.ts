// Class names compared and stored the server's way (holiscene_schema/classes.py: class_key,
// normalise_class_name); shared_schema/vectors/class_names.json holds both sides together.
import { CLASS_ALIASES, NYU40_CLASSES } from "@holiscene/schema";

const ALIASES: Record<string, string> = CLASS_ALIASES;
const CLASSES = new Set<string>(NYU40_CLASSES);

/** A name as the lookups compare it: trimmed, lower case, words joined by one "_". */
export const classKey = (text: string): string =>
  text
    .toLowerCase()
    .split(/[\s_-]+/)
    .filter((word) => word.length > 0)
    .join("_");

/** The NYU-40 class a name is stored as, a plural ("chairs", "couches") too; null when the
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
  return null;
}
