// From the Relation Network's probabilities to a support tree, in the browser: the TypeScript
// twin of backend/src/holiscene/learning/decode.py (`decode_supports`). Each object without a
// pinned supporter takes its best (supporter, type) that closes no cycle, the most confident
// objects first, so a doubtful object cannot block a sure one. Two readings of the scores, as
// in Python: "network" (the probabilities alone) and "network+priors" (Eq. 4.1: the network's
// five most probable supporter categories, each instance's probability times the counted
// prior P(supporter class | class, type); the pipeline's default). Re-decoding with an
// annotator's corrections pinned is how the remaining predictions follow a correction without
// a server round trip. Both sides are tested against shared_schema/vectors/support_decode.json.

import { STRUCTURAL_SUPPORT_TYPES } from "@holiscene/schema";
import { STRUCTURAL_COLUMNS, SUPPORT_TYPE_ORDER, type SupportTypeName } from "./supportModel";
import type { SupportPriors } from "./supportPriors";

export type DecodeMode = "network" | "network+priors";
const TOP_CATEGORIES = 5; // |SC(O_i)| in Eq. 4.1

/** What "network+priors" needs: the objects' classes (in the order of `ids`) and the priors. */
export interface PriorScoring {
  classes: readonly string[];
  priors: SupportPriors;
}

export interface DecodedSupport {
  child: string;
  parent: string;
  type: SupportTypeName;
  /** The answer's share of the object's probability (itself left out); null when pinned. */
  probability: number | null;
  pinned: boolean;
}

export interface PinnedSupport {
  child: string;
  parent: string;
  type: string;
}

export interface Candidate {
  parent: string;
  type: SupportTypeName;
  probability: number;
}

/** The key of one answer, as `excluded` takes it. */
export const answerKey = (child: string, parent: string, type: string) =>
  `${child}\u0000${parent}\u0000${type}`;

/**
 * Every (supporter, type) for object `row`, best first, probabilities renormalised without
 * the object itself. `probabilities` is the [N, N + 3, T] table, flat and row-major.
 */
export function rankedCandidates(
  probabilities: ArrayLike<number>,
  row: number,
  ids: readonly string[],
  withPriors: PriorScoring | null = null,
): Candidate[] {
  const columns = [...ids, ...STRUCTURAL_COLUMNS];
  const types = SUPPORT_TYPE_ORDER.length;
  const offset = row * columns.length * types;
  // Not the object itself; and the room's parts hold things up one way only (the floor from
  // below; walls and the ceiling from behind), whatever the network says.
  const impossible = (c: number, t: number) =>
    c === row ||
    (c >= ids.length && STRUCTURAL_SUPPORT_TYPES[columns[c] as string] !== SUPPORT_TYPE_ORDER[t]);
  const scores = Array.from({ length: columns.length * types }, (_, k) =>
    impossible(Math.floor(k / types), k % types) ? 0 : (probabilities[offset + k] as number),
  );
  if (withPriors) {
    const { classes, priors } = withPriors;
    const columnClass = (c: number) =>
      (c < ids.length ? classes[c] : STRUCTURAL_COLUMNS[c - ids.length]) as string;
    const mass = new Map<string, number>(); // in the order categories first appear, as in Python
    for (let c = 0; c < columns.length; c++) {
      let sum = 0;
      for (let t = 0; t < types; t++) sum += scores[c * types + t] as number;
      mass.set(columnClass(c), (mass.get(columnClass(c)) ?? 0) + sum);
    }
    const top = new Set(
      [...mass.keys()]
        .sort((a, b) => (mass.get(b) as number) - (mass.get(a) as number))
        .slice(0, TOP_CATEGORIES),
    );
    const child = classes[row] as string;
    for (let c = 0; c < columns.length; c++) {
      const cls = columnClass(c);
      SUPPORT_TYPE_ORDER.forEach((type, t) => {
        const prior = top.has(cls) ? priors.conditional(cls, child, type) : 0;
        scores[c * types + t] = (scores[c * types + t] as number) * prior;
      });
    }
    // The priors ruled everything out: fall back to the network alone.
    if (scores.every((v) => v <= 0)) return rankedCandidates(probabilities, row, ids);
  }
  let total = 0;
  for (const v of scores) total += v;
  const found: Candidate[] = [];
  for (let c = 0; c < columns.length; c++) {
    if (c === row) continue;
    SUPPORT_TYPE_ORDER.forEach((type, t) => {
      const p = scores[c * types + t] as number;
      found.push({ parent: columns[c] as string, type, probability: total > 0 ? p / total : 0 });
    });
  }
  // Array sort is stable, like Python's sorted: equals keep the column-then-type order.
  return found.sort((a, b) => b.probability - a.probability);
}

/** Whether `parent` holding up `child` closes a loop through the supports decided so far. */
function closesCycle(child: string, parent: string, parentOf: ReadonlyMap<string, string>) {
  const seen = new Set<string>();
  for (let node: string | undefined = parent; node !== undefined; node = parentOf.get(node)) {
    if (node === child) return true;
    if (seen.has(node)) return false; // a loop among the pinned ones: not ours to report
    seen.add(node);
  }
  return false;
}

/**
 * A supporter for every object, in the order of `ids`: the pinned ones as they are, the rest
 * decoded. `excluded` (answerKey) are answers the annotator rejected; an object whose every
 * answer is excluded or closes a cycle gets none. With `withPriors`, Eq. 4.1's reading.
 */
export function decodeSupports(
  probabilities: ArrayLike<number>,
  ids: readonly string[],
  pinned: readonly PinnedSupport[] = [],
  excluded: ReadonlySet<string> = new Set(),
  withPriors: PriorScoring | null = null,
): DecodedSupport[] {
  const known = new Set(ids);
  const decided = new Map<string, DecodedSupport>();
  const parentOf = new Map<string, string>();
  for (const p of pinned) {
    if (!known.has(p.child) || decided.has(p.child)) continue;
    decided.set(p.child, {
      child: p.child,
      parent: p.parent,
      type: p.type as SupportTypeName,
      probability: null,
      pinned: true,
    });
    parentOf.set(p.child, p.parent);
  }
  const rankings = ids
    .map((id, row) => ({ id, row }))
    .filter(({ id }) => !decided.has(id))
    .map(({ id, row }) => {
      const ranked = rankedCandidates(probabilities, row, ids, withPriors);
      return {
        id,
        // The order of decisions uses the best answer before exclusions, as in Python.
        top: ranked[0]?.probability ?? 0,
        ranked: ranked.filter((c) => !excluded.has(answerKey(id, c.parent, c.type))),
      };
    });
  rankings.sort((a, b) => b.top - a.top);
  for (const { id, ranked } of rankings) {
    const answer = ranked.find((c) => !closesCycle(id, c.parent, parentOf));
    if (!answer) continue;
    decided.set(id, { child: id, ...answer, pinned: false });
    parentOf.set(id, answer.parent);
  }
  return ids.flatMap((id) => {
    const support = decided.get(id);
    return support ? [support] : [];
  });
}
