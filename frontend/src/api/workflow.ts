// Accounts, sessions and the annotation workflow (see backend api/routes/auth, users, workflow).
import type {
  CurrentUser,
  Dashboard,
  LoginResult,
  NewUser,
  SceneSummary,
  SceneWorkflow,
  UserInfo,
} from "@holiscene/schema";
import { inBackground, jsonBody, request } from "./client";

export type SceneState = SceneSummary["state"];
export type Role = CurrentUser["role"];

/** Every state in workflow order (the dashboard and the list filter show them so). */
export const SCENE_STATES: readonly SceneState[] = [
  "new",
  "predicted",
  "in_annotation",
  "submitted",
  "accepted",
  "rejected",
];

export const stateLabel = (state: SceneState) => state.replace("_", " ");

/** A state badge's text and its data-state (its colour): an archived scene says so first. */
export const stateBadge = (state: SceneState, archived: boolean) =>
  archived
    ? { text: `archived · ${stateLabel(state)}`, key: "archived" }
    : { text: stateLabel(state), key: state };

const sceneUrl = (sceneId: string) => `/scenes/${encodeURIComponent(sceneId)}`;
const userUrl = (name: string) => `/users/${encodeURIComponent(name)}`;

export const authApi = {
  /** Who is asking; 401 (an ApiError) when nobody is logged in and login is required. */
  me: (signal?: AbortSignal) => request<CurrentUser>("/auth/me", { signal }),

  /** The session comes back as an HttpOnly cookie; the page never sees the token. */
  login: (name: string, password: string) =>
    request<LoginResult>("/auth/login", jsonBody({ name, password, token: false })),

  logout: () => request<void>("/auth/logout", { method: "POST" }),

  changePassword: (currentPassword: string, newPassword: string) =>
    request<void>(
      "/auth/password",
      jsonBody({ current_password: currentPassword, new_password: newPassword }),
    ),
};

export const usersApi = {
  list: (signal?: AbortSignal) => request<UserInfo[]>("/users", { signal }),
  create: (user: NewUser) => request<UserInfo>("/users", jsonBody(user)),
  setRole: (name: string, role: Role) =>
    request<UserInfo>(userUrl(name), { ...jsonBody({ role }), method: "PATCH" }),
  resetPassword: (name: string, password: string) =>
    request<void>(`${userUrl(name)}/password`, jsonBody({ password })),
  /** Disable (no login, sessions ended) or enable an account again. */
  setDisabled: (name: string, disabled: boolean) =>
    request<UserInfo>(`${userUrl(name)}/${disabled ? "disable" : "enable"}`, { method: "POST" }),
};

/** Which scenes a list holds: those in use (the default), the archived ones, or both. */
export type ArchivedScope = "exclude" | "only" | "include";

export const workflowApi = {
  /** `background`: the page refreshes the list by itself (not activity, see BACKGROUND_HEADER). */
  listScenes: (
    state: SceneState | null,
    signal?: AbortSignal,
    background = false,
    archived: ArchivedScope = "exclude",
  ) => {
    const query = new URLSearchParams();
    if (state) query.set("state", state);
    if (archived !== "exclude") query.set("archived", archived);
    const search = query.size > 0 ? `?${query}` : "";
    return request<SceneSummary[]>(
      `/scenes${search}`,
      background ? inBackground({ signal }) : { signal },
    );
  },

  /** Archive a scene (admin): out of the lists and "Next scene", read only, kept whole. */
  archive: (sceneId: string) =>
    request<SceneSummary>(`${sceneUrl(sceneId)}/archive`, { method: "POST" }),

  /** Bring an archived scene back (admin). */
  unarchive: (sceneId: string) =>
    request<SceneSummary>(`${sceneUrl(sceneId)}/unarchive`, { method: "POST" }),

  /** Take the next scene to annotate (404 when none is waiting). */
  next: () => request<SceneSummary>("/scenes/next", { method: "POST" }),

  /** The scene waiting longest for the caller's review; nothing is assigned (404: none). */
  /** `after`: the scene open now; the next one after it in the queue comes back. */
  nextToReview: (after?: string) =>
    request<SceneSummary>(
      `/scenes/next-review${after ? `?after=${encodeURIComponent(after)}` : ""}`,
    ),

  /** `background`: the page checks by itself (not activity, see BACKGROUND_HEADER). */
  get: (sceneId: string, signal?: AbortSignal, background = false) =>
    request<SceneWorkflow>(
      `${sceneUrl(sceneId)}/workflow`,
      background ? inBackground({ signal }) : { signal },
    ),

  take: (sceneId: string) => request<SceneSummary>(`${sceneUrl(sceneId)}/take`, { method: "POST" }),

  /** Give back a scene in annotation: it waits for the next annotator again. */
  release: (sceneId: string, revision: number) =>
    request<SceneWorkflow>(`${sceneUrl(sceneId)}/release`, jsonBody({ revision })),

  submit: (sceneId: string, revision: number) =>
    request<SceneWorkflow>(`${sceneUrl(sceneId)}/submit`, jsonBody({ revision })),

  /** Take a submission back before a reviewer decides (its annotator). */
  withdraw: (sceneId: string, revision: number) =>
    request<SceneWorkflow>(`${sceneUrl(sceneId)}/withdraw`, jsonBody({ revision })),

  accept: (sceneId: string, revision: number) =>
    request<SceneWorkflow>(`${sceneUrl(sceneId)}/accept`, jsonBody({ revision })),

  reject: (sceneId: string, revision: number, comment: string) =>
    request<SceneWorkflow>(`${sceneUrl(sceneId)}/reject`, jsonBody({ revision, comment })),

  secondAnnotation: (sceneId: string, revision: number) =>
    request<SceneWorkflow>(`${sceneUrl(sceneId)}/second-annotation`, jsonBody({ revision })),

  dashboard: (signal?: AbortSignal) => request<Dashboard>("/dashboard", { signal }),
};
