// What the status line adds when an action's new objects need a second look: a mask the server
// could not cut (it is the whole box), or a new object on top of one of its class already
// there (a faint detector box accepted over the bed that was labelled: two beds).
import type { SceneDocument, SceneObject } from "@holiscene/schema";
import { boxIou } from "../inference/detectorTensor";
import { classText } from "./classNames";
import type { ObjectEdit } from "./objectEditor";

/** A new object of a class is taken for a second one of something labelled already when it
 * overlaps that object this much (IoU), or lies this much inside it or around it (the share
 * of the smaller box covered by the other). */
const TWIN_IOU = 0.3;
const TWIN_COVER = 0.8;

/** The ids of the objects the edits added. */
const addedIds = (edits: readonly ObjectEdit[], withoutMask: boolean) =>
  new Set(
    edits.flatMap((e) => (e.kind === "add_object" && !(withoutMask && e.mask) ? [e.id] : [])),
  );

/**
 * What to say of new objects the server could not cut out (their mask is their whole box,
 * which then covers whatever else is in it): "" when every one was cut.
 */
export function uncutNote(edits: readonly ObjectEdit[], doc: SceneDocument): string {
  const added = addedIds(edits, true);
  const uncut = (doc.scene.objects ?? []).filter(
    (o) => added.has(o.id) && o.mask?.source === "box",
  );
  if (uncut.length === 0) return "";
  const ids = uncut.map((o) => o.id).join(", ");
  // What to do first: the status line shows its start, the rest on a click or hover.
  const whose = uncut.length === 1 ? `${ids}'s mask is its` : `the masks of ${ids} are their`;
  const them = uncut.length === 1 ? "it" : "them";
  return ` But ${whose} whole box: fix with Brush, Eraser or Refine (the automatic cut could not separate ${them}).`;
}

/** How much of the smaller of two boxes the other covers. */
function coverOfSmaller(a: readonly number[], b: readonly number[]): number {
  const [a0, a1, a2, a3] = a as [number, number, number, number];
  const [b0, b1, b2, b3] = b as [number, number, number, number];
  const inter =
    Math.max(Math.min(a2, b2) - Math.max(a0, b0), 0) *
    Math.max(Math.min(a3, b3) - Math.max(a1, b1), 0);
  const smaller = Math.min((a2 - a0) * (a3 - a1), (b2 - b0) * (b3 - b1));
  return smaller > 0 ? inter / smaller : 0;
}

const isTwin = (added: SceneObject, other: SceneObject) =>
  other.class === added.class &&
  (boxIou(added.bbox, other.bbox) > TWIN_IOU ||
    coverOfSmaller(added.bbox, other.bbox) > TWIN_COVER);

/**
 * What to say of new objects that overlap an object of their class that was there before
 * (" d3 overlaps o0, also a bed: if they are the same bed, select d3 and remove it
 * (Delete)."): "" when
 * none does. Objects added together are not compared with each other.
 */
export function twinNote(edits: readonly ObjectEdit[], doc: SceneDocument): string {
  const added = addedIds(edits, false);
  const objects = doc.scene.objects ?? [];
  const before = objects.filter((o) => !added.has(o.id));
  return objects
    .filter((o) => added.has(o.id))
    .flatMap((o) => {
      const twin = before.find((other) => isTwin(o, other));
      if (!twin) return [];
      const cls = classText(o.class);
      return [
        ` ${o.id} overlaps ${twin.id}, also a ${cls}: if they are the same ${cls}, select ${o.id} and remove it (Delete).`,
      ];
    })
    .join("");
}

/** Both notes, the mask's first. */
export const newObjectNotes = (edits: readonly ObjectEdit[], doc: SceneDocument): string =>
  uncutNote(edits, doc) + twinNote(edits, doc);
