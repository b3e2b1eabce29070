// What an object action will do to the scene, shown before the server answers (so an edit is
// redrawn at once, not after the round trip): a removal takes the object and every support it
// took part in away, a class or box change shows the new class or box, and a restore puts
// back the object and its supports (or, for a revert, the whole scene) of a revision seen
// before. The server's revision replaces the prediction as soon as it comes (masks the server
// cuts are only known then, so a new object without a mask is shown by its box until the
// answer brings the mask).
import type { SceneDocument, SceneObject, SupportRelation } from "@holiscene/schema";
import { storedClass } from "./classNames";
import type { NewObject, ObjectEdit } from "./objectEditor";

const involves = (support: SupportRelation, id: string) =>
  support.child === id || support.parent === id;

/** A new object as the server will store it, less what only the server knows (its support). */
function newObject(edit: NewObject, cls: SceneObject["class"]): SceneObject {
  return {
    id: edit.id,
    class: cls,
    bbox: edit.bbox,
    mask: edit.mask ?? null,
    score: edit.score ?? null,
    source: edit.source,
    source_class: null,
    set_by_person: ["object"],
    box_3d: null,
    corners_3d: null,
    box_3d_confidence: null,
    mesh: null,
    note: null,
  };
}

/**
 * `doc` after `edits`, as far as can be told here; null when an edit cannot be foreseen (a
 * restore from a revision not at hand, a class the server would refuse, an id in use).
 * `revision(n)`: a document of revision n seen before, if any.
 */
export function predictDocument(
  doc: SceneDocument,
  edits: readonly ObjectEdit[],
  revision: (number: number) => SceneDocument | undefined,
): SceneDocument | null {
  let scene = doc.scene;
  let objects = [...(scene.objects ?? [])];
  let supports = [...(scene.supports ?? [])];
  for (const edit of edits) {
    if (edit.kind === "restore_scene") {
      const then = revision(edit.from_revision);
      if (!then) return null;
      // The photo, its depth and the name stay, as the server keeps them.
      scene = { ...then.scene, name: scene.name, image: scene.image, depth: scene.depth };
      objects = [...(scene.objects ?? [])];
      supports = [...(scene.supports ?? [])];
      continue;
    }
    const index = objects.findIndex((o) => o.id === edit.id);
    const object = objects[index];
    if (edit.kind === "add_object") {
      const cls = storedClass(edit.class);
      if (object || !cls) return null;
      objects.push(newObject(edit, cls as SceneObject["class"]));
    } else if (edit.kind === "remove_object") {
      if (!object) return null;
      objects = objects.filter((o) => o.id !== edit.id);
      supports = supports.filter((s) => !involves(s, edit.id));
    } else if (edit.kind === "set_class") {
      const cls = storedClass(edit.class);
      if (!object || !cls) return null;
      objects[index] = { ...object, class: cls as typeof object.class };
    } else if (edit.kind === "set_bbox") {
      if (!object) return null;
      objects[index] = { ...object, bbox: edit.bbox };
    } else if (edit.kind === "restore_object") {
      const then = revision(edit.from_revision);
      if (!then) return null;
      const old = then.scene.objects?.find((o) => o.id === edit.id);
      objects = objects.filter((o) => o.id !== edit.id);
      supports = supports.filter((s) => !involves(s, edit.id));
      if (old) {
        objects.splice(Math.min(index < 0 ? objects.length : index, objects.length), 0, old);
        const present = new Set(objects.map((o) => o.id));
        const held = (id: string) => present.has(id) || ["floor", "wall", "ceiling"].includes(id);
        const back = (then.scene.supports ?? []).filter(
          (s) => involves(s, edit.id) && held(s.child) && held(s.parent),
        );
        // A child has one supporter: the restored one replaces the one it has now.
        const children = new Set(back.map((s) => s.child));
        supports = [...supports.filter((s) => !children.has(s.child)), ...back];
      }
    } else return null;
  }
  return { ...doc, scene: { ...scene, objects, supports } };
}
