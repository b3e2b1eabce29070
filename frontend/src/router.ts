// Hash routes: `#/` is the scene list, `#/scenes/{id}` a scene, `#/models` the Relation
// Network models and `#/models/detector` the object detectors (admin), `#/dashboard` the
// workflow dashboard (`#/dashboard/accounts`: scrolled to its accounts, for admins), `#/login`
// the login page.
import type { ModelInfo } from "@holiscene/schema";

/** The kinds of model the registry holds. */
export type ModelKind = ModelInfo["kind"];

export type Route =
  | { page: "list" }
  | { page: "scene"; sceneId: string }
  | { page: "models"; kind: ModelKind }
  | { page: "dashboard"; accounts?: true }
  | { page: "login" }
  | { page: "unknown" };

export function parseRoute(hash: string): Route {
  const path = hash.replace(/^#/, "") || "/";
  if (path === "/") return { page: "list" };
  if (/^\/models\/?$/.test(path)) return { page: "models", kind: "relation" };
  const models = /^\/models\/(relation|detector)\/?$/.exec(path);
  if (models?.[1]) return { page: "models", kind: models[1] as ModelKind };
  if (/^\/dashboard\/?$/.test(path)) return { page: "dashboard" };
  if (/^\/dashboard\/accounts\/?$/.test(path)) return { page: "dashboard", accounts: true };
  if (/^\/login\/?$/.test(path)) return { page: "login" };
  const scene = /^\/scenes\/([^/]+)\/?$/.exec(path);
  if (scene?.[1]) return { page: "scene", sceneId: decodeURIComponent(scene[1]) };
  return { page: "unknown" };
}

type LeaveGuard = () => string | null;
let leaveGuard: LeaveGuard | null = null;

/**
 * Register what leaving the current page would lose (a message, or null when nothing).
 * Returns the function that removes the guard.
 */
export function setLeaveGuard(guard: LeaveGuard): () => void {
  leaveGuard = guard;
  return () => {
    if (leaveGuard === guard) leaveGuard = null;
  };
}

/** Whether to leave the page: yes unless it would lose something and the user says no. */
export function confirmLeave(): boolean {
  const message = leaveGuard?.();
  return !message || window.confirm(message);
}
