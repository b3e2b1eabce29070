// Support priors counted from labelled scenes (a model's priors.json): how often class p holds
// up class c by type t. The TypeScript twin of backend/src/holiscene/learning/priors.py, for
// the decoder's Eq. 4.1 reading (treeDecode.ts), which the pipeline uses by default.
import { STRUCTURAL_COLUMNS } from "./supportModel";

export interface PriorsFile {
  smoothing?: number;
  /** child class -> "supporter class|type" -> count */
  counts: Record<string, Record<string, number>>;
}

const SMOOTHING = 0.5; // priors.py's constant (the file records it too)

export class SupportPriors {
  private readonly background = new Map<string, number>();
  private readonly rowTotals = new Map<string, number>();
  private readonly typeTotals = new Map<string, number>();
  /** Every supporter class counted for any child, and the structural ones. */
  readonly supporters: ReadonlySet<string>;

  constructor(private readonly counts: PriorsFile["counts"]) {
    const totals = new Map<string, number>();
    let grand = 0;
    const seen = new Set<string>(STRUCTURAL_COLUMNS);
    for (const [child, row] of Object.entries(counts)) {
      let sum = 0;
      for (const [key, count] of Object.entries(row)) {
        totals.set(key, (totals.get(key) ?? 0) + count);
        grand += count;
        sum += count;
        seen.add(key.split("|")[0] as string);
      }
      this.rowTotals.set(child, sum);
    }
    for (const [key, count] of totals) this.background.set(key, count / (grand || 1));
    this.supporters = seen;
  }

  static fromJson(data: PriorsFile): SupportPriors {
    return new SupportPriors(data.counts);
  }

  /** P(supporter class, type | child class), smoothed. */
  joint(parentCls: string, childCls: string, type: string): number {
    const row = this.counts[childCls] ?? {};
    const key = `${parentCls}|${type}`;
    const background = this.background.get(key) ?? 0;
    const rowTotal = this.rowTotals.get(childCls) ?? 0;
    if (Object.keys(row).length === 0 && !background) {
      // Nothing counted at all: every structural supporter below is equally likely.
      return type === "below" ? 1 / STRUCTURAL_COLUMNS.length : 0;
    }
    return ((row[key] ?? 0) + SMOOTHING * background) / (rowTotal + SMOOTHING);
  }

  /** P(supporter class | child class, type), as Eq. 4.1 uses it. */
  conditional(parentCls: string, childCls: string, type: string): number {
    const cacheKey = `${childCls}|${type}`;
    let total = this.typeTotals.get(cacheKey);
    if (total === undefined) {
      total = 0;
      for (const p of this.supporters) total += this.joint(p, childCls, type);
      this.typeTotals.set(cacheKey, total);
    }
    return total > 0 ? this.joint(parentCls, childCls, type) / total : 0;
  }
}
