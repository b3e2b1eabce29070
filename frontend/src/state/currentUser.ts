// Who is using the app: the account (or the local single-user mode's admin), as the server
// said at start-up or at login. Null until known, and after logging out.
import type { CurrentUser } from "@holiscene/schema";
import type { Role } from "../api/workflow";

const RANK: Record<Role, number> = { annotator: 1, reviewer: 2, admin: 3 };

let current: CurrentUser | null = null;
const listeners = new Set<(user: CurrentUser | null) => void>();

export function getCurrentUser(): CurrentUser | null {
  return current;
}

export function setCurrentUser(user: CurrentUser | null): void {
  current = user;
  for (const listener of listeners) listener(user);
}

export function onCurrentUserChange(listener: (user: CurrentUser | null) => void): () => void {
  listeners.add(listener);
  return () => listeners.delete(listener);
}

/** Roles are nested as on the server: an admin may do what a reviewer may, and so on. */
export function hasRole(role: Role, user: CurrentUser | null = current): boolean {
  return user !== null && RANK[user.role] >= RANK[role];
}
