// Entry point: who is logged in, the header, and the hash router.
import "./styles.css";
import type { CurrentUser } from "@holiscene/schema";
import { sessionEvents } from "./api/client";
import { ApiError } from "./api/errors";
import { authApi } from "./api/workflow";
import { button, el } from "./dom";
import { confirmLeave, parseRoute } from "./router";
import { bindAuthorInput, setAuthorFallback } from "./state/author";
import { getCurrentUser, onCurrentUserChange, setCurrentUser } from "./state/currentUser";
import { savesLanded } from "./state/savesInFlight";
import { mountDashboardPage } from "./views/dashboard/dashboardPage";
import { mountShortcutHelp } from "./views/help/shortcutHelp";
import { mountLoginPage } from "./views/login/loginPage";
import { mountModelsPage } from "./views/models/modelsPage";
import { mountScenePage } from "./views/scene/scenePage";
import { mountSceneList } from "./views/sceneList/sceneListView";

const app = document.querySelector<HTMLElement>("#app");
const authorInput = document.querySelector<HTMLInputElement>("#author-input");
const userArea = document.querySelector<HTMLElement>("#user-area");
if (!app || !authorInput || !userArea) {
  throw new Error("index.html lacks #app, #author-input or #user-area");
}
bindAuthorInput(authorInput);
mountShortcutHelp(document.body);

function mount(root: HTMLElement): () => void {
  const route = parseRoute(window.location.hash);
  const user = getCurrentUser();
  if (!user || route.page === "login") {
    // Logged out: the login page, whatever the address (it is where to go after login).
    document.body.dataset.page = "login";
    document.title = "Log in · HoliScene";
    if (user) {
      window.location.hash = "#/";
      return () => {};
    }
    return mountLoginPage(root, loggedIn);
  }
  document.body.dataset.page = route.page;
  switch (route.page) {
    case "list":
      document.title = "HoliScene";
      return mountSceneList(root);
    case "scene":
      document.title = `${route.sceneId} · HoliScene`;
      return mountScenePage(root, route.sceneId);
    case "models":
      document.title = "Models · HoliScene";
      return mountModelsPage(root, route.kind);
    case "dashboard":
      document.title = "Dashboard · HoliScene";
      return mountDashboardPage(root, route.accounts === true);
    case "unknown":
      document.title = "HoliScene";
      root.replaceChildren(
        el(
          "p",
          { className: "page-message" },
          "No such page. ",
          el("a", { text: "All scenes", attrs: { href: "#/" } }),
        ),
      );
      return () => {};
  }
}

function renderUserArea(user: CurrentUser | null): void {
  document.body.dataset.localMode = String(user?.local_mode ?? false);
  setAuthorFallback(user?.name ?? null);
  if (!user) {
    userArea?.replaceChildren();
    return;
  }
  const logout = button("Log out", { testid: "logout", onClick: () => void logOut() });
  userArea?.replaceChildren(
    el("a", { text: "Dashboard", testid: "dashboard-link", attrs: { href: "#/dashboard" } }),
    // Every role may look at the models (admins retrain and roll back there): one click away
    // from any page, not only from the scene list.
    el("a", {
      text: "Models",
      testid: "models-link",
      attrs: {
        href: "#/models",
        title: "The Relation Network and the object detector: retrain, compare, roll back",
      },
    }),
    // The accounts are at the dashboard's foot: an admin gets there in one click.
    ...(user.role === "admin" && !user.local_mode
      ? [
          el("a", {
            text: "Accounts",
            testid: "accounts-link",
            attrs: {
              href: "#/dashboard/accounts",
              title: "Add people, change roles, reset passwords",
            },
          }),
        ]
      : []),
    el(
      "span",
      {
        testid: "current-user",
        attrs: {
          title: user.local_mode
            ? "Single-user mode: the server listens on 127.0.0.1 only and has no accounts yet"
            : "",
        },
      },
      el("strong", { text: user.name }),
      " ",
      el("span", {
        className: "user-role",
        text: user.local_mode ? `(${user.role}, single-user mode)` : `(${user.role})`,
        testid: "current-role",
      }),
    ),
    ...(user.local_mode ? [] : [logout]),
  );
}

let dispose: () => void = () => {};
let shownHash = window.location.hash;

function remount(): void {
  dispose();
  dispose = mount(app as HTMLElement);
}

function loggedIn(user: CurrentUser): void {
  setCurrentUser(user);
  remount();
}

async function logOut(): Promise<void> {
  if (!confirmLeave()) return;
  // Leave the page first: it sends its last edits, which must land while the session holds
  // (what does not land stays in this person's drafts for their next visit).
  dispose();
  dispose = () => {};
  await savesLanded();
  try {
    await authApi.logout();
  } finally {
    setCurrentUser(null);
    // Whoever logs in next starts at the scene list, not on this person's page.
    history.replaceState(null, "", "#/");
    shownHash = "#/";
    remount();
  }
}

/** The session ended while a page was open: log in again over it, so nothing on the page
 * (unsaved edits included) is lost; then the page carries on. */
function loginOverPage(reason: string | null): void {
  if (document.querySelector("[data-testid='login-overlay']")) return;
  const before = getCurrentUser();
  const inner = el("div");
  const overlay = el(
    "div",
    {
      className: "login-overlay",
      testid: "login-overlay",
      attrs: { role: "dialog", "aria-modal": "true", "aria-label": "Log in again" },
    },
    el("p", {
      className: "alert alert--info",
      testid: "login-overlay-reason",
      // The server says why (expired, idle, or the account was disabled: logging in again
      // as the same person cannot help then).
      text: reason
        ? `${reason.charAt(0).toUpperCase()}${reason.slice(1)}. Nothing on this page was lost: log in to carry on.`
        : "Your session ended. Log in again to carry on; nothing on this page was lost.",
    }),
    inner,
  );
  document.body.append(overlay);
  mountLoginPage(
    inner,
    (user) => {
      overlay.remove();
      setCurrentUser(user);
      if (user.name !== before?.name) remount(); // someone else: show their view
    },
    before?.name,
  );
}

sessionEvents.onUnauthorized = (reason) => {
  if (getCurrentUser()) loginOverPage(reason);
};
onCurrentUserChange(renderUserArea);

async function start(): Promise<void> {
  try {
    setCurrentUser(await authApi.me());
  } catch (error) {
    if (!(error instanceof ApiError && error.status === 401)) {
      app?.replaceChildren(
        el("p", {
          className: "alert alert--error",
          attrs: { role: "alert" },
          text: `Could not reach the server: ${error instanceof Error ? error.message : String(error)}`,
        }),
      );
      return;
    }
    setCurrentUser(null);
  }
  remount();
}

window.addEventListener("hashchange", () => {
  if (!confirmLeave()) {
    // Stay: put the address back without another hashchange.
    history.replaceState(null, "", shownHash || "#/");
    return;
  }
  shownHash = window.location.hash;
  remount();
  // Keyboard focus starts on the new page, unless the page put it somewhere (the login's
  // password field when the name is known).
  if (!app.contains(document.activeElement)) app.focus({ preventScroll: true });
  window.scrollTo(0, 0);
});

void start();
