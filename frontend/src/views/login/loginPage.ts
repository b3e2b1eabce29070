// The login page: shown whenever the server answers 401 (no session, or it ended).
import type { CurrentUser } from "@holiscene/schema";
import { ApiError } from "../../api/errors";
import { authApi } from "../../api/workflow";
import { button, el, hiddenErrorAlert, labelledField } from "../../dom";
import "../workflow/workflow.css";

/** Why the next login page is shown, and whose name to fill in (said once, then forgotten). */
let nextNotice: { text: string; name: string } | null = null;

export function noticeForNextLogin(text: string, name: string): void {
  nextNotice = { text, name };
}

/** `knownName`: who was logged in when the session ended (the name is filled in for them). */
export function mountLoginPage(
  container: HTMLElement,
  onLoggedIn: (user: CurrentUser) => void,
  knownName?: string,
): () => void {
  const name = el("input", {
    testid: "login-name",
    attrs: {
      type: "text",
      name: "username",
      autocomplete: "username",
      required: true,
      maxlength: 64,
      autocapitalize: "none",
      spellcheck: "false",
    },
  });
  const password = el("input", {
    testid: "login-password",
    attrs: {
      type: "password",
      name: "password",
      autocomplete: "current-password",
      required: true,
      maxlength: 256,
    },
  });
  const submit = button("Log in", { className: "primary", testid: "login-submit", type: "submit" });
  const error = hiddenErrorAlert("login-error");
  const form = el(
    "form",
    { className: "card login-form", testid: "login-form" },
    el("h1", { text: "Log in to HoliScene" }),
    labelledField("User name", name),
    labelledField("Password", password),
    error,
    el("div", { className: "form-actions" }, submit),
    el("p", {
      className: "field-hint",
      text: "No account yet? Ask an admin to make one for you.",
    }),
  );
  form.addEventListener("submit", async (event) => {
    event.preventDefault();
    submit.disabled = true;
    error.hidden = true;
    try {
      const result = await authApi.login(name.value.trim().toLowerCase(), password.value);
      onLoggedIn(result.user);
    } catch (err) {
      error.hidden = false;
      error.textContent =
        err instanceof ApiError ? err.message : `Could not log in: ${String(err)}`;
      password.select();
    } finally {
      submit.disabled = false;
    }
  });
  const notice = nextNotice;
  nextNotice = null;
  if (notice) {
    form.insertBefore(
      el("p", { className: "alert alert--info", testid: "login-notice", text: notice.text }),
      form.querySelector("h1")?.nextSibling ?? null,
    );
  }
  container.replaceChildren(el("div", { className: "login-page" }, form));
  const fill = knownName ?? notice?.name;
  if (fill) {
    name.value = fill;
    password.focus();
  } else name.focus();
  return () => {};
}
