// The TypeScript support-tree decoder against the Python one (shared vectors written by
// `python -m holiscene.twin_vectors.support_decode` from holiscene.learning.decode), and what the
// browser adds: rejected answers left out.
import { describe, expect, it } from "vitest";
import vectorsText from "../../../shared_schema/vectors/support_decode.json?raw";
import { STRUCTURAL_COLUMNS, SUPPORT_TYPE_ORDER } from "./supportModel";
import { type PriorsFile, SupportPriors } from "./supportPriors";
import { answerKey, decodeSupports, type PriorScoring, rankedCandidates } from "./treeDecode";

interface DecodeCase {
  name: string;
  mode: "network" | "network+priors";
  classes?: string[];
  priors?: PriorsFile;
  ids: string[];
  probabilities: { shape: number[]; data: number[] };
  pinned: { child: string; parent: string; type: string }[];
  expected: { child: string; parent: string; type: string; confidence: number | null }[];
}

const vectors = JSON.parse(vectorsText) as {
  structural_columns: string[];
  support_types: string[];
  cases: DecodeCase[];
};

describe("support-tree decoder, against the Python decoder", () => {
  it("reads the same contract", () => {
    expect(vectors.structural_columns).toEqual([...STRUCTURAL_COLUMNS]);
    expect(vectors.support_types).toEqual([...SUPPORT_TYPE_ORDER]);
    expect(vectors.cases.length).toBeGreaterThanOrEqual(10);
    expect(vectors.cases.filter((c) => c.mode === "network+priors").length).toBeGreaterThanOrEqual(
      8,
    );
  });

  for (const c of vectors.cases) {
    it(`decodes ${c.name} like Python`, () => {
      const withPriors: PriorScoring | null =
        c.mode === "network+priors" && c.priors && c.classes
          ? { classes: c.classes, priors: SupportPriors.fromJson(c.priors) }
          : null;
      const decoded = decodeSupports(c.probabilities.data, c.ids, c.pinned, new Set(), withPriors);
      expect(decoded.map((d) => [d.child, d.parent, d.type])).toEqual(
        c.expected.map((e) => [e.child, e.parent, e.type]),
      );
      const pinned = new Set(c.pinned.map((p) => p.child));
      decoded.forEach((d, i) => {
        const confidence = c.expected[i]?.confidence;
        expect(d.pinned).toBe(pinned.has(d.child));
        if (d.pinned) return;
        // Python stores round(score, 4).
        expect(Math.abs((d.probability ?? -1) - (confidence ?? 2))).toBeLessThanOrEqual(5.0001e-5);
      });
    });
  }
});

describe("the browser's additions", () => {
  const mutual = vectors.cases.find((c) => c.name === "mutual-pair");
  if (!mutual) throw new Error("the vectors lack the mutual-pair case");

  it("never answers with the object itself and sums to one", () => {
    const ranked = rankedCandidates(mutual.probabilities.data, 0, mutual.ids);
    expect(ranked.some((r) => r.parent === "o0")).toBe(false);
    expect(ranked.reduce((sum, r) => sum + r.probability, 0)).toBeCloseTo(1, 12);
    expect(ranked[0]).toMatchObject({ parent: "o1", type: "below" });
  });

  it("takes the next answer when the best one was rejected", () => {
    const excluded = new Set([answerKey("o0", "o1", "below")]);
    const decoded = decodeSupports(mutual.probabilities.data, mutual.ids, [], excluded);
    // o0 gives up o1; o1 is then free to rest on o0, its own best.
    expect(decoded.map((d) => [d.child, d.parent])).toEqual([
      ["o0", "floor"],
      ["o1", "o0"],
    ]);
  });

  it("a correction changes another object's answer: no cycles", () => {
    const free = decodeSupports(mutual.probabilities.data, mutual.ids);
    // Each would rest on the other: the surer one does, the other cannot (a cycle).
    const resting = free.filter((d) => ["o0", "o1"].includes(d.parent)).map((d) => d.child);
    expect(resting).toHaveLength(1);
    const winner = resting[0] as string;
    const other = winner === "o0" ? "o1" : "o0";
    expect(free.find((d) => d.child === winner)?.parent).toBe(other);
    // A person puts the other one on it: the winner's answer changes.
    const corrected = decodeSupports(mutual.probabilities.data, mutual.ids, [
      { child: other, parent: winner, type: "below" },
    ]);
    expect(corrected.find((d) => d.child === winner)?.parent).not.toBe(other);
    expect(corrected.find((d) => d.child === other)).toMatchObject({
      parent: winner,
      pinned: true,
    });
  });

  it("leaves an object without a supporter when every answer is excluded", () => {
    const excluded = new Set(
      rankedCandidates(mutual.probabilities.data, 1, mutual.ids).map((r) =>
        answerKey("o1", r.parent, r.type),
      ),
    );
    const decoded = decodeSupports(mutual.probabilities.data, mutual.ids, [], excluded);
    expect(decoded.map((d) => d.child)).toEqual(["o0"]);
  });
});
