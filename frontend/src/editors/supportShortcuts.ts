// The keyboard for support editing: every action on the selected edge has a key, listed in
// the help overlay (?) by the shortcut registry.
import { registerShortcut } from "../shortcuts";
import type { SceneSession } from "../state/sceneSession";
import {
  type ActionResult,
  acceptAll,
  acceptEdge,
  flipType,
  rejectEdge,
  removeSupport,
  selectNext,
  setSupporter,
} from "./supportActions";

const SCOPE = "Support editing";

export function mountSupportShortcuts(session: SceneSession): () => void {
  /** Run an action on the selected object, or say that one must be selected first. */
  const onSelected = (action: (s: SceneSession, child: string) => ActionResult) => () => {
    const child = session.selected;
    session.say(child ? action(session, child) : "Select an arrow or object first (click it).");
  };
  // Keys that change supports are off while the scene is read only; the others only select.
  const keys: [string | string[], string, () => void, boolean?][] = [
    [
      "A",
      "Accept the selected edge (the prediction, or the model's suggestion)",
      onSelected(acceptEdge),
    ],
    ["Shift+A", "Accept every remaining edge as shown", () => session.say(acceptAll(session))],
    ["R", "Reject the selected edge: the model's next answer is suggested", onSelected(rejectEdge)],
    ["T", "Flip the selected edge between below and behind", onSelected(flipType)],
    [
      ["Shift+Delete", "Shift+Backspace"],
      "Remove the selected object's supporter (Delete alone removes the object)",
      onSelected(removeSupport),
    ],
    [
      "F",
      "The floor holds up the selected object",
      onSelected((s, c) => setSupporter(s, c, "floor")),
    ],
    ["W", "A wall holds up the selected object", onSelected((s, c) => setSupporter(s, c, "wall"))],
    [
      "C",
      "The ceiling holds up the selected object",
      onSelected((s, c) => setSupporter(s, c, "ceiling")),
    ],
    ["N", "Select the next object still to check", () => session.say(selectNext(session, 1)), true],
    [
      "Shift+N",
      "Select the previous object still to check",
      () => session.say(selectNext(session, -1)),
      true,
    ],
    [
      "Escape",
      "Clear the selection",
      () => {
        session.say(null);
        session.select(null);
      },
      true,
    ],
  ];
  const editable = () => session.editable;
  const removers = keys.map(([k, description, run, reads]) =>
    registerShortcut({
      keys: k,
      description,
      scope: SCOPE,
      run,
      enabled: reads ? undefined : editable,
    }),
  );
  return () => {
    for (const remove of removers) remove();
  };
}
