// The lines of a revision's diff in the history: each support changed, objects added or
// removed, and whether the room layout moved.
import type { SceneDocument } from "@holiscene/schema";
import { el } from "../../../dom";
import { describeChange, diffScenes } from "../../../state/revisionDiff";

/** What `after` changed from `before` (null: `after` is the imported scene). */
export function diffLines(before: SceneDocument | null, after: SceneDocument): HTMLLIElement[] {
  const diff = before
    ? diffScenes(before.scene, after.scene)
    : { supports: [], objectsAdded: [], objectsRemoved: [], layoutChanged: false };
  const lines = [
    ...diff.supports.map((c) =>
      el("li", {
        text: describeChange(c),
        attrs: { "data-child": c.child, "data-kind": c.kind },
      }),
    ),
    ...(diff.objectsAdded.length > 0
      ? [el("li", { text: `objects added: ${diff.objectsAdded.join(", ")}` })]
      : []),
    ...(diff.objectsRemoved.length > 0
      ? [el("li", { text: `objects removed: ${diff.objectsRemoved.join(", ")}` })]
      : []),
    ...(diff.layoutChanged ? [el("li", { text: "room layout changed" })] : []),
  ];
  if (lines.length > 0) return lines;
  return [el("li", { text: before ? "no change to supports" : "the imported scene" })];
}
