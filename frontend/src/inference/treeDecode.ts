// From the Relation Network's probabilities to a support tree, in the browser: the TypeScript
// twin of backend/src/holiscene/learning/decode.py (`decode_supports`, "network" mode, which
// the pipeline runs). Each object without a pinned supporter takes its most probable
// (supporter, type) that closes no cycle, the most confident objects first, so a doubtful
// object cannot block a sure one. Re-decoding with an annotator's corrections pinned is how
// the remaining predictions follow a correction without a server round trip. Both sides are
// tested against shared_schema/vectors/support_decode.json.
import { STRUCTURAL_COLUMNS, SUPPORT_TYPE_ORDER, type SupportTypeName } from "./supportModel";

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
): Candidate[] {
  const columns = [...ids, ...STRUCTURAL_COLUMNS];
  const types = SUPPORT_TYPE_ORDER.length;
  const offset = row * columns.length * types;
  let total = 0;
  for (let c = 0; c < columns.length; c++) {
    if (c === row) continue;
    for (let t = 0; t < types; t++) total += probabilities[offset + c * types + t] as number;
  }
  const found: Candidate[] = [];
  for (let c = 0; c < columns.length; c++) {
    if (c === row) continue;
    SUPPORT_TYPE_ORDER.forEach((type, t) => {
      const p = probabilities[offset + c * types + t] as number;
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
 * answer is excluded or closes a cycle gets none.
 */
export function decodeSupports(
  probabilities: ArrayLike<number>,
  ids: readonly string[],
  pinned: readonly PinnedSupport[] = [],
  excluded: ReadonlySet<string> = new Set(),
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
      const ranked = rankedCandidates(probabilities, row, ids);
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
