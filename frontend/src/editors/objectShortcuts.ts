// Keys for the selected object itself (in every photo tool): Delete removes it (its supports
// go; undo brings everything back), Shift+C changes its class with the class picker (as the
// class button of its line in the object list does).
import type { SceneObject } from "@holiscene/schema";
import { registerShortcut } from "../shortcuts";
import { classKey, classText } from "../state/classNames";
import type { ObjectEditor } from "../state/objectEditor";
import type { SceneSession } from "../state/sceneSession";
import { classHints } from "../views/scene/classHints";
import { type PickerOptions, pickClass } from "../views/scene/classPicker";
import { objectName, screenRect } from "./boxes/boxEdits";

export const REMOVE_OBJECT_KEYS = ["Delete"];
export const SET_CLASS_KEY = "Shift+C";
const SCOPE = "Objects";

/** The selected object; without one the person is asked to select one. */
function selectedOrAsk(session: SceneSession): SceneObject | undefined {
  const object = session.selectedObject;
  if (!object) session.say("Select an object first (click it).");
  return object;
}

/** Remove the selected object (one undoable action). */
export async function removeSelected(editor: ObjectEditor): Promise<void> {
  const { session } = editor;
  const object = selectedOrAsk(session);
  if (!object) return;
  session.select(null);
  await editor.apply([{ kind: "remove_object", id: object.id }], `remove ${objectName(object)}`);
}

/** Pick a new class for the selected object (near its box on `svg`). */
export async function changeSelectedClass(editor: ObjectEditor, svg: SVGSVGElement): Promise<void> {
  const object = selectedOrAsk(editor.session);
  if (!object) return;
  await changeClass(editor, object, screenRect(svg, object.bbox));
  // Opened by a key over the photo: the keyboard lands on the object's row, not the page's
  // start (Tab then goes on from the object, as a keyboard user expects).
  if (document.activeElement === document.body)
    document
      .querySelector<HTMLElement>(`[data-testid="object-class-${CSS.escape(object.id)}"]`)
      ?.focus({ preventScroll: true });
}

/** Pick a new class for `object` in the class picker shown beside `near` (client pixels). */
export async function changeClass(
  editor: ObjectEditor,
  object: SceneObject,
  near: PickerOptions["near"],
): Promise<void> {
  const { session } = editor;
  const cls = await pickClass({
    near,
    title: `Class of ${objectName(object)}`,
    objects: session.objects,
    current: object.class,
    likely: classHints.at(session.sceneId, object.bbox),
  });
  // The plain class is a change for an object shown with an imported name ("chair
  // (sofa_chair)"): the server then drops that name.
  if (!cls || classKey(cls) === (object.source_class ?? object.class)) return;
  await editor.apply(
    [{ kind: "set_class", id: object.id, class: cls }],
    `${objectName(object)} → ${classText(cls)}`,
  );
}

export function mountObjectShortcuts(editor: ObjectEditor, svg: SVGSVGElement): () => void {
  const editable = () => editor.session.editable;
  const removers = [
    registerShortcut({
      keys: REMOVE_OBJECT_KEYS,
      description:
        "Remove the selected object (its mask and supports too; Ctrl+Z brings them back)",
      scope: SCOPE,
      run: () => void removeSelected(editor),
      enabled: editable,
    }),
    registerShortcut({
      keys: SET_CLASS_KEY,
      description: "Change the selected object's class (type to search, Enter or 1-9 to pick)",
      scope: SCOPE,
      run: () => void changeSelectedClass(editor, svg),
      enabled: editable,
    }),
  ];
  return () => {
    for (const remove of removers) remove();
  };
}
