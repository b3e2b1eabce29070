// What an annotator does to the support graph, one function per action, each one undoable
// step on the session. The photo's mouse handling and the keyboard shortcuts both call these.
// Each returns a message for the user when the action could not be done (null: done).
import type { SceneSession } from "../state/sceneSession";
import {
  type Edit,
  isStructural,
  onlyType,
  type SupportType,
  typeFor,
} from "../state/supportGraph";

export type ActionResult = string | null;

const other = (type: SupportType): SupportType => (type === "below" ? "behind" : "below");

/** Objects that need a supporter (room structure does not), in the scene's order. */
export function supportable(session: SceneSession): string[] {
  return session.objects.filter((o) => !isStructural(o.class)).map((o) => o.id);
}

/**
 * The objects from `parent` along the supporters as shown to the one resting on `child`
 * (`parent` first), or null when `parent` does not rest on `child`, so that making `parent`
 * hold up `child` closes no loop.
 */
function loopThrough(session: SceneSession, child: string, parent: string): string[] | null {
  const shown = session.shown();
  const path: string[] = [];
  for (let node: string | undefined = parent; node !== undefined; node = shown.get(node)?.parent) {
    if (node === child) return path;
    if (path.includes(node)) return null;
    path.push(node);
  }
  return null;
}

/**
 * Make `parent` hold up `child`; the type follows the supporter unless it is kept. When
 * `parent` rests (through guesses) on `child`, the least confident guess on that loop goes
 * and is rejected, so the model suggests that object's next answer; a loop of people's
 * edges is refused.
 */
export function setSupporter(session: SceneSession, child: string, parent: string): ActionResult {
  if (child === parent) return `${child} cannot hold itself up.`;
  const loop = isStructural(parent) ? null : loopThrough(session, child, parent);
  const shown = session.shown();
  const guesses = (loop ?? []).filter((id) => !session.isResolved(id));
  if (loop && guesses.length === 0) return `${parent} rests on ${child}: pick another supporter.`;
  const type = typeFor(parent, session.displayed(child));
  const edits: Edit[] = [{ kind: "set_support", child, parent, type }];
  const rejected: { child: string; parent: string; type: string }[] = [];
  if (loop) {
    const confidence = (id: string) => shown.get(id)?.confidence ?? 0;
    const broken = guesses.reduce((a, b) => (confidence(b) < confidence(a) ? b : a));
    const guess = shown.get(broken);
    edits.push({ kind: "remove_support", child: broken });
    if (guess) rejected.push({ child: broken, parent: guess.parent, type: guess.type });
  }
  session.edit(`${child} on ${parent}`, edits, rejected);
  return null;
}

/** Below <-> behind for the object's edge (the suggestion's, if the model proposes one). */
export function flipType(session: SceneSession, child: string): ActionResult {
  const current = session.displayed(child);
  if (!current) return `${child} has no supporter to flip.`;
  const only = onlyType(current.parent);
  if (only) return `The ${current.parent} holds ${child} up from ${only} only.`;
  const type = other(current.type);
  session.edit(`${child}: ${type}`, [{ kind: "set_support", child, parent: current.parent, type }]);
  return null;
}

/** Leave the object without a supporter (a suggestion alone is rejected instead). */
export function removeSupport(session: SceneSession, child: string): ActionResult {
  const current = session.displayed(child);
  if (!current) return `${child} has no supporter.`;
  if (!current.support) return rejectEdge(session, child);
  session.edit(`remove ${child}'s supporter`, [{ kind: "remove_support", child }]);
  return null;
}

/** Confirm the edge shown for the object (the predicted one, or the model's suggestion). */
export function acceptEdge(session: SceneSession, child: string): ActionResult {
  const current = session.displayed(child);
  if (!current) return `${child} has no supporter to accept: pick one.`;
  session.edit(`accept ${child} on ${current.parent}`, [
    { kind: "set_support", child, parent: current.parent, type: typeFor(current.parent, current) },
  ]);
  return null;
}

/**
 * Say the edge shown is wrong. A guess is removed and a suggestion dropped, and the model
 * will not propose that answer again (its next answer shows as a suggestion); a person's
 * edge is just removed.
 */
export function rejectEdge(session: SceneSession, child: string): ActionResult {
  const current = session.displayed(child);
  if (!current) return `${child} has no edge to reject.`;
  if (current.support?.source === "manual") {
    session.edit(`remove ${child}'s supporter`, [{ kind: "remove_support", child }]);
    return null;
  }
  const edits: Edit[] = current.suggested ? [] : [{ kind: "remove_support", child }];
  session.edit(`reject ${child} on ${current.parent}`, edits, [
    { child, parent: current.parent, type: current.type },
  ]);
  return null;
}

/** Objects whose edge no person has confirmed yet (a guess, a suggestion, or nothing). */
export function unresolved(session: SceneSession): string[] {
  return supportable(session).filter((id) => !session.isResolved(id));
}

/** Confirm every remaining edge as shown (guesses and suggestions) in one action. */
export function acceptAll(session: SceneSession): ActionResult {
  const edits: Edit[] = unresolved(session).flatMap((child) => {
    const current = session.displayed(child);
    return current
      ? [
          {
            kind: "set_support" as const,
            child,
            parent: current.parent,
            type: typeFor(current.parent, current),
          },
        ]
      : [];
  });
  if (edits.length === 0) return "Nothing left to accept.";
  session.edit(`accept ${edits.length} remaining`, edits);
  return null;
}

/** Select the next (or previous) object that still needs a look, wrapping around. */
export function selectNext(session: SceneSession, step: 1 | -1): ActionResult {
  const all = supportable(session);
  const todo = new Set(unresolved(session));
  const pool = todo.size > 0 ? all.filter((id) => todo.has(id)) : all;
  if (pool.length === 0) return "No objects.";
  const at = session.selected ? all.indexOf(session.selected) : -1;
  const ordered = step === 1 ? all : [...all].reverse();
  const start = at < 0 ? -1 : ordered.indexOf(all[at] as string);
  for (let k = 1; k <= ordered.length; k++) {
    const id = ordered[(start + k) % ordered.length] as string;
    if (pool.includes(id)) {
      session.select(id);
      return null;
    }
  }
  return null;
}
