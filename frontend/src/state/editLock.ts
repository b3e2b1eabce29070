// Whether a scene may be edited now, and if not why: the read-only banner's text. The server
// says so on the scene and on its workflow (`editable`, `editable_reason`: it refuses edits of
// submitted and accepted scenes, of scenes someone else annotates, ...); without its word (an
// older server), the workflow state decides: submitted and accepted scenes are read only.
import type { SceneWorkflow } from "@holiscene/schema";

type SceneState = SceneWorkflow["state"];

/** Why the scene is read only: a headline for the banner, and the server's reason. */
export interface EditLock {
  title: string;
  reason: string | null;
}

/** The server's word on editing, as the scene or its workflow carried it (if at all). */
export interface EditPermission {
  editable?: boolean | null;
  editable_reason?: string | null;
}

/** The banner's headline for a read-only scene in this state. */
function lockTitle(state: SceneState | null | undefined): string {
  switch (state) {
    case "submitted":
      return "Submitted for review — read only";
    case "accepted":
      return "Accepted — read only";
    default:
      return "Read only";
  }
}

/**
 * The lock of a scene in `state` (null: unknown yet) given the server's latest word on it
 * (`permission`, null or without `editable`: none); null when it may be edited.
 */
export function editLock(
  state: SceneState | null | undefined,
  permission: EditPermission | null,
): EditLock | null {
  const editable = permission?.editable;
  if (editable === true) return null;
  if (editable === false) {
    return { title: lockTitle(state), reason: permission?.editable_reason ?? null };
  }
  return state === "submitted" || state === "accepted"
    ? { title: lockTitle(state), reason: null }
    : null;
}

/** The lock as one line (what an editing key says when pressed on a read-only scene). */
export function lockText(lock: EditLock): string {
  return lock.reason ? `${lock.title}: ${lock.reason}` : lock.title;
}

/** A control's tooltip: what it does, or, on a read-only scene, why it is off. */
export function titleUnlessLocked(title: string, lock: EditLock | null): string {
  return lock ? `Not available now. ${lockText(lock)}` : title;
}
