// Live suggestions from the Relation Network's probabilities, scored once per scene: after
// every edit the tree is decoded again as the pipeline decodes it (with the model's counted
// priors, Eq. 4.1, when it has them), with the objects a person has set pinned and the
// rejected answers left out (treeDecode.ts), so a correction moves the remaining guesses at
// once, without the server. An object whose decoded answer differs from its guess, or whose
// guess was rejected, gets that answer as a suggestion.
import type { SceneSession, SuggestedSupport, Suggester } from "../state/sceneSession";
import { isStructural } from "../state/supportGraph";
import type { SupportPriors } from "./supportPriors";
import { answerKey, decodeSupports, type PinnedSupport } from "./treeDecode";

export interface SceneProbabilities {
  /** The model's objects, in the order of the table's rows. */
  ids: readonly string[];
  /** [N, N + 3, 2] probabilities, flat. */
  probabilities: ArrayLike<number>;
  /** With both: Eq. 4.1's reading (the pipeline's); without: the network alone. */
  classes?: readonly string[];
  priors?: SupportPriors | null;
}

export function makeSuggester({
  ids,
  probabilities,
  classes,
  priors,
}: SceneProbabilities): Suggester {
  const withPriors = priors && classes ? { classes, priors } : null;
  return (session: SceneSession) => {
    const shown = session.shown();
    // A missing supporter is nobody's decision in a scene no support stage has run on (a
    // photo imported without the pipeline), nor for an object a person added; a supporter
    // removed by hand and not saved yet is one.
    const supportsPredicted = (session.doc.scene.stages ?? []).some((stage) =>
      stage.name.startsWith("supports_"),
    );
    const awaitsSupporter = (id: string) =>
      !session.isPending(id) &&
      (!supportsPredicted || (session.object(id)?.set_by_person ?? []).includes("object"));
    const pinned: PinnedSupport[] = [];
    const excluded = new Set<string>();
    for (const id of ids) {
      const support = shown.get(id);
      if (support && session.isResolved(id)) pinned.push(support);
      for (const key of session.rejectedAnswers(id)) {
        const cut = key.lastIndexOf("|");
        excluded.add(answerKey(id, key.slice(0, cut), key.slice(cut + 1)));
      }
    }
    const suggestions = new Map<string, SuggestedSupport>();
    // Scores of an older revision (until the new one is scored) name objects that may be gone.
    const present = (id: string) => isStructural(id) || session.object(id) !== undefined;
    for (const d of decodeSupports(probabilities, ids, pinned, excluded, withPriors)) {
      if (d.pinned || d.probability === null) continue;
      if (!present(d.child) || !present(d.parent)) continue;
      const current = shown.get(d.child);
      if (current && current.parent === d.parent && current.type === d.type) continue;
      // An object a person left without a supporter stays so, unless they rejected answers
      // (then the next one is wanted) or it awaits its first supporter.
      if (!current && session.rejectedAnswers(d.child).size === 0 && !awaitsSupporter(d.child))
        continue;
      suggestions.set(d.child, {
        child: d.child,
        parent: d.parent,
        type: d.type,
        probability: d.probability,
      });
    }
    return suggestions;
  };
}
