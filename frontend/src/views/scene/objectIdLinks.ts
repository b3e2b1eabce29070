// Object ids in a line of text (a pipeline warning, a line of the revision history) as links
// that select their object on the photo, so whatever a line names is one click away.
import { button, el } from "../../dom";

/** How the pipeline and the detector name objects (o12, d3, o4_1): a token that looks like one
 * but is not in the scene names an object removed since. */
const OBJECT_ID = /^[od]\d+(_\d+)?$/;

export type ObjectTextPart = { text: string } | { id: string } | { removed: string };

/** A text cut at the ids of the scene's objects: each `id` part can become a link that selects
 * its object ("masks: o3, o5" -> "masks: ", o3, ", ", o5); an id no longer in the scene is a
 * `removed` part. */
export function textWithObjectIds(text: string, ids: ReadonlySet<string>): ObjectTextPart[] {
  const parts: ObjectTextPart[] = [];
  let plain = "";
  // Ids are word-like tokens; anything else stays text.
  for (const token of text.split(/([A-Za-z]\w*)/)) {
    const part = ids.has(token) ? { id: token } : OBJECT_ID.test(token) ? { removed: token } : null;
    if (part) {
      if (plain) parts.push({ text: plain });
      plain = "";
      parts.push(part);
    } else plain += token;
  }
  if (plain) parts.push({ text: plain });
  return parts;
}

/** `text` with the ids of `ids` as buttons calling `select`, and other ids struck through with
 * `removedTitle(id)` as their tooltip. */
export function linkObjectIds(
  text: string,
  ids: ReadonlySet<string>,
  select: (id: string) => void,
  removedTitle: (id: string) => string,
): (HTMLElement | string)[] {
  return textWithObjectIds(text, ids).map((part) =>
    "id" in part
      ? button(part.id, {
          className: "object-id-link",
          title: `Select ${part.id}`,
          onClick: () => select(part.id),
        })
      : "removed" in part
        ? el("del", {
            className: "object-id-removed",
            text: part.removed,
            attrs: { title: removedTitle(part.removed) },
          })
        : part.text,
  );
}
