// The lines of a revision's diff in the history: each support changed, objects added,
// removed or changed (class, box, mask; 3D boxes and shapes in one line), and whether the room
// layout or camera moved.
import type { SceneDocument } from "@holiscene/schema";
import { el } from "../../../dom";
import { describeChange, diffScenes } from "../../../state/revisionDiff";
import { plural } from "../../../state/sceneSession";

/** What `after` changed from `before` (null: `after` is the imported scene); `restoreLink`
 * gives a removed object's "restore" link (null: none, e.g. it is back in the scene). */
export function diffLines(
  before: SceneDocument | null,
  after: SceneDocument,
  restoreLink: (id: string) => HTMLElement | null = () => null,
): HTMLLIElement[] {
  const diff = before
    ? diffScenes(before.scene, after.scene)
    : {
        supports: [],
        objectsAdded: [],
        objectsRemoved: [],
        objectsChanged: [],
        layoutChanged: false,
      };
  const drawn = diff.objectsChanged.filter((c) => c.drawn.length > 0);
  const placed = diff.objectsChanged.filter((c) => c.placed.length > 0).map((c) => c.id);
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
      ? [
          el(
            "li",
            { attrs: { "data-removed": diff.objectsRemoved.join(" ") } },
            "objects removed: ",
            ...diff.objectsRemoved.flatMap((id, i) => {
              const link = restoreLink(id);
              return [i > 0 ? ", " : "", id, ...(link ? [" ", link] : [])];
            }),
          ),
        ]
      : []),
    ...drawn.map((c) =>
      el("li", {
        text: `${c.id}: ${c.drawn.join(", ")}`,
        attrs: { "data-object": c.id },
      }),
    ),
    ...(placed.length > 0
      ? [
          el("li", {
            text: `3D box or shape of ${plural(placed.length, "object")}: ${placed.join(", ")}`,
          }),
        ]
      : []),
    ...(diff.layoutChanged ? [el("li", { text: "room layout or camera changed" })] : []),
  ];
  if (lines.length > 0) return lines;
  return [
    el("li", {
      text: before ? "no change to objects, supports or the room" : "the imported scene",
    }),
  ];
}
