// What the class picker lists for what was typed: the NYU-40 classes (room structure aside:
// the layout gives walls, floor and ceiling) and the names other datasets use for them, best
// match first (the whole name, its start, a word's start, anywhere), then the classes the
// detector saw at the box (classHints.ts), then the most used. A free name the server would
// resolve by its words ("office chair", "chiar": classWords.ts) offers its class as a whole
// match, so what the picker offers is what an import of that name stores.
import { CLASS_ALIASES, NYU40_CLASSES, STRUCTURAL_SUPPORTERS } from "@holiscene/schema";
import { classKey, storedClass } from "../../state/classNames";

export interface ClassOption {
  /** What is sent as the class: an NYU-40 class or a known alias of one. */
  name: string;
  /** The NYU-40 class it is stored as. */
  cls: string;
}

const structural = new Set<string>(STRUCTURAL_SUPPORTERS);

/** Every option: the NYU-40 classes first, in their order, then the aliases. */
export const CLASS_OPTIONS: readonly ClassOption[] = [
  ...NYU40_CLASSES.filter((c) => !structural.has(c)).map((c) => ({ name: c, cls: c })),
  ...Object.entries(CLASS_ALIASES)
    .filter(([alias, cls]) => alias !== cls && !structural.has(cls))
    .map(([alias, cls]) => ({ name: alias, cls })),
];

const OPTION_NAMES = new Set(CLASS_OPTIONS.map((o) => o.name));

/** How well `name` matches `query`: 0 the whole name, 1 its start, 2 a word's start, 3 inside. */
function matchRank(name: string, query: string, resolved: string | null): number | null {
  if (query === "") return 1;
  if (name === query || name === resolved) return 0;
  if (name.startsWith(query)) return 1;
  if (name.split("_").some((word) => word.startsWith(query))) return 2;
  return name.includes(query) ? 3 : null;
}

/**
 * The options matching `query`, best first: by match, then in the order of `likely` (NYU-40
 * classes the detector saw at the box, most likely first), then by use (`uses`: picks or
 * objects per NYU-40 class), then classes before aliases, then in the vocabulary's order.
 */
export function rankClasses(
  query: string,
  uses: ReadonlyMap<string, number>,
  limit = 12,
  likely: readonly string[] = [],
): ClassOption[] {
  const key = classKey(query);
  // A name the options hold is offered as itself; a free name, as the class it resolves to.
  const resolved = OPTION_NAMES.has(key) ? null : storedClass(query);
  const hinted = new Map(likely.map((cls, i) => [cls, i]));
  const scored: {
    option: ClassOption;
    rank: number;
    hint: number;
    used: number;
    alias: number;
    index: number;
  }[] = [];
  CLASS_OPTIONS.forEach((option, index) => {
    const rank = matchRank(option.name, key, resolved);
    if (rank === null) return;
    const alias = option.name === option.cls ? 0 : 1;
    // With nothing typed, only the classes: the aliases would just repeat them.
    if (key === "" && alias) return;
    const hint = hinted.get(option.cls) ?? likely.length;
    scored.push({ option, rank, hint, used: uses.get(option.cls) ?? 0, alias, index });
  });
  scored.sort(
    (a, b) =>
      a.rank - b.rank ||
      a.hint - b.hint ||
      b.used - a.used ||
      a.alias - b.alias ||
      a.index - b.index,
  );
  return beforeLongerForms(scored.map((s) => s.option)).slice(0, limit);
}

/**
 * A name listed after a longer form of itself ("sofa" after "sofa_chair", which a scene of
 * chairs ranks high) moves up to just before it: "sof" typed means the sofa until more of
 * "sofa chair" is typed.
 */
function beforeLongerForms(options: ClassOption[]): ClassOption[] {
  const ordered = [...options];
  let i = 0;
  while (i < ordered.length) {
    const longer = ordered[i] as ClassOption;
    const j = ordered.findIndex((o, k) => k > i && longer.name.startsWith(`${o.name}_`));
    if (j < 0) {
      i++;
      continue;
    }
    // The shorter form takes place i and is looked at next (it may have one of its own).
    const [shorter] = ordered.splice(j, 1);
    ordered.splice(i, 0, shorter as ClassOption);
  }
  return ordered;
}
