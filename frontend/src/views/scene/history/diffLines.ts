// The lines of a revision's diff in the history: objects added and removed, each support
// changed, objects changed (class, box, mask; 3D boxes and shapes in one line), and whether the room
// layout or camera moved.
import type { SceneDocument } from "@holiscene/schema";
import { el } from "../../../dom";
import { describeChange, diffScenes } from "../../../state/revisionDiff";
import { plural } from "../../../state/sceneSession";

/** What `after` changed from `before` (null: `after` is the imported scene); `restoreLink`
 * gives a removed object's "restore" link (null: none, e.g. it is back in the scene), and
 * `linkIds` turns the object ids in a line's text into links (objectIdLinks.ts). */
export function diffLines(
  before: SceneDocument | null,
  after: SceneDocument,
  restoreLink: (id: string) => HTMLElement | null = () => null,
  linkIds: (text: string) => (HTMLElement | string)[] = (text) => [text],
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
  // Objects added and removed first: a supporter set on an object added in the same span
  // reads as a change to an object that was there, unless the line says it is new.
  const added = new Set(diff.objectsAdded);
  const lines = [
    ...(diff.objectsAdded.length > 0
      ? [el("li", {}, ...linkIds(`objects added: ${diff.objectsAdded.join(", ")}`))]
      : []),
    ...(diff.objectsRemoved.length > 0
      ? [
          el(
            "li",
            { attrs: { "data-removed": diff.objectsRemoved.join(" ") } },
            "objects removed: ",
            // Restorable ones with their "restore"; one back in the scene since, as a link.
            ...diff.objectsRemoved.flatMap((id, i) => {
              const link = restoreLink(id);
              return [i > 0 ? ", " : "", ...(link ? [id, " ", link] : linkIds(id))];
            }),
          ),
        ]
      : []),
    ...diff.supports.map((c) =>
      el(
        "li",
        { attrs: { "data-child": c.child, "data-kind": c.kind } },
        ...linkIds(`${added.has(c.child) ? "(new) " : ""}${describeChange(c)}`),
      ),
    ),
    ...drawn.map((c) =>
      el("li", { attrs: { "data-object": c.id } }, ...linkIds(`${c.id}: ${c.drawn.join(", ")}`)),
    ),
    ...(placed.length > 0
      ? [
          el(
            "li",
            {},
            ...linkIds(
              `3D box or shape of ${plural(placed.length, "object")}: ${placed.join(", ")}`,
            ),
          ),
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
