// The dashboard's accounts card (admins): every account with its role (changed in place), a
// password reset and disabling it (or enabling it again), and the form that adds an account.
import type { UserInfo } from "@holiscene/schema";
import { ApiError } from "../../api/errors";
import { type Role, usersApi } from "../../api/workflow";
import { button, el, formatTime, labelledField } from "../../dom";
import { getCurrentUser, setCurrentUser } from "../../state/currentUser";
import { noticeForNextLogin } from "../login/loginPage";

const ROLES: readonly Role[] = ["annotator", "reviewer", "admin"];
const NAME_RULE = "lower-case letters, digits, _ . - (starting with a letter or digit)";

/** Where an account action reports: a line of news, or an error. */
interface Report {
  say(text: string): void;
  fail(error: unknown): void;
}

/** A field for a new password, saying the server's rule before it refuses one. */
function newPasswordInput(testid: string): HTMLInputElement {
  return el("input", {
    testid,
    attrs: {
      type: "password",
      required: true,
      minlength: 10,
      autocomplete: "new-password",
      placeholder: "10 characters or more",
      title: "At least 10 characters, not a common password",
    },
  });
}

/** Why the server would refuse to demote or disable `user` (the last enabled admin), or
 * null: the row says so up front instead of asking first and failing after. */
export function lastAdminReason(user: UserInfo, users: readonly UserInfo[]): string | null {
  const admins = users.filter((u) => u.role === "admin" && !u.disabled);
  if (user.disabled || user.role !== "admin" || admins.length !== 1) return null;
  return `${user.name} is the only admin: make another account admin first`;
}

/** An account's row: its role (a select that changes it), "Reset password…" and Disable;
 * `lastAdmin` says why the role and Disable are locked (see lastAdminReason). */
function userRow(
  user: UserInfo,
  lastAdmin: string | null,
  report: Report,
  onChange: () => void,
): HTMLTableRowElement {
  const role = el(
    "select",
    {
      testid: `role-select-${user.name}`,
      attrs: {
        "aria-label": `Role of ${user.name}`,
        disabled: lastAdmin !== null,
        title: lastAdmin ?? undefined,
      },
    },
    ...ROLES.map((r) => el("option", { text: r, attrs: { value: r, selected: r === user.role } })),
  );
  role.addEventListener("change", async () => {
    report.say(""); // the last message was about another action
    const question = `Make ${user.name} an admin? Admins manage accounts, retrain and promote models, and may take over any scene.`;
    if (role.value === "admin" && !window.confirm(question)) {
      role.value = user.role;
      return;
    }
    try {
      await usersApi.setRole(user.name, role.value as Role);
      report.say(`${user.name} is now ${role.value}.`);
      onChange();
    } catch (err) {
      role.value = user.role;
      report.fail(err);
    }
  });
  const reset = button("Reset password…", { testid: `reset-password-${user.name}` });
  // A password field in the row, not the browser's prompt (which shows what is typed).
  const newPassword = newPasswordInput(`new-password-${user.name}`);
  newPassword.setAttribute("aria-label", `New password for ${user.name}`);
  const resetForm = el(
    "form",
    { className: "password-reset", testid: `password-reset-${user.name}` },
    newPassword,
    button("Set", { className: "primary", type: "submit", testid: `set-password-${user.name}` }),
    button("Cancel", { onClick: () => showReset(false) }),
  );
  const showReset = (open: boolean) => {
    if (open) report.say(""); // the last message was about another action
    resetForm.hidden = !open;
    reset.hidden = open;
    newPassword.value = "";
    if (open) newPassword.focus();
  };
  resetForm.hidden = true;
  reset.addEventListener("click", () => showReset(true));
  resetForm.addEventListener("submit", async (event) => {
    event.preventDefault();
    try {
      await usersApi.resetPassword(user.name, newPassword.value);
      showReset(false);
      report.say(`New password set for ${user.name}; their sessions ended.`);
    } catch (err) {
      report.fail(err);
    }
  });
  const access = button(user.disabled ? "Enable" : "Disable…", {
    testid: `${user.disabled ? "enable" : "disable"}-account-${user.name}`,
    disabled: lastAdmin !== null,
    title:
      lastAdmin ??
      (user.disabled
        ? "Let this account log in again"
        : "Stop this account logging in and end its sessions (its work stays)"),
  });
  access.addEventListener("click", async () => {
    report.say("");
    const question =
      user.name === getCurrentUser()?.name
        ? "Disable your own account? You are logged out at once and cannot log in until " +
          "another admin enables it; your scenes and labels stay."
        : `Disable ${user.name}? They are logged out and cannot log in until enabled again; their scenes and labels stay.`;
    if (!user.disabled && !window.confirm(question)) return;
    try {
      await usersApi.setDisabled(user.name, !user.disabled);
      report.say(user.disabled ? `${user.name} can log in again.` : `${user.name} is disabled.`);
      onChange();
    } catch (err) {
      report.fail(err);
    }
  });
  const status = user.disabled
    ? `disabled${user.disabled_at ? ` since ${formatTime(user.disabled_at)}` : ""}`
    : "active";
  return el(
    "tr",
    { testid: `account-${user.name}`, className: user.disabled ? "is-disabled" : "" },
    el("th", { text: user.name, attrs: { scope: "row" } }),
    el("td", {}, role),
    el("td", { text: formatTime(user.created_at) }),
    el("td", { text: status, testid: `account-status-${user.name}` }),
    el("td", { className: "account-actions" }, reset, resetForm, access),
  );
}

/** The form that adds an account; `onAdded` is told after each one. */
function newUserForm(report: Report, onAdded: () => Promise<void>): HTMLFormElement {
  const name = el("input", {
    testid: "new-user-name",
    attrs: {
      type: "text",
      required: true,
      maxlength: 64,
      autocomplete: "off",
      pattern: "[a-z0-9][a-z0-9_.\\-]*",
      // The browser shows the title when the pattern refuses a name.
      title: NAME_RULE,
    },
  });
  // In single-user mode the first account must be an admin (the server refuses another).
  const first = getCurrentUser()?.local_mode === true;
  const role = el(
    "select",
    { testid: "new-user-role" },
    ...ROLES.map((r) =>
      el("option", { text: r, attrs: { value: r, selected: first && r === "admin" } }),
    ),
  );
  const password = newPasswordInput("new-user-password");
  const create = button("Add account", {
    className: "primary",
    testid: "new-user-submit",
    type: "submit",
  });
  const form = el(
    "form",
    { className: "user-form", testid: "new-user-form" },
    labelledField("Name", name),
    labelledField("Role", role),
    labelledField("Password", password),
    create,
    // Under the row, not under the name: inside the field it pushed the name's input above
    // the role's and the password's.
    el("p", {
      className: "field-hint user-form-hint",
      text: first
        ? `${NAME_RULE} The first account must be an admin; once it exists, everyone logs in.`
        : NAME_RULE,
    }),
  );
  // The browser refusing a field (its own bubble) is an answer too: an older message would
  // sit beside it as if it were about this. ("invalid" does not bubble: caught on the way.)
  form.addEventListener("invalid", () => report.say(""), true);
  form.addEventListener("submit", async (event) => {
    event.preventDefault();
    report.say(""); // the last answer is about another request
    create.disabled = true;
    try {
      const user = await usersApi.create({
        name: name.value.trim(),
        role: role.value as Role,
        password: password.value,
      });
      form.reset();
      if (first) {
        // The server has accounts now: everyone logs in, this page too.
        noticeForNextLogin(
          `${user.name} is the first account: from now on everyone logs in, you too.`,
          user.name,
        );
        setCurrentUser(null);
        window.location.hash = "#/login";
        return;
      }
      report.say(`Added ${user.name} (${user.role}).`);
      await onAdded();
    } catch (err) {
      report.fail(err);
    } finally {
      create.disabled = false;
    }
  });
  return form;
}

/** The accounts card; `onChange` is told when an account was added or its role changed. */
export function accountsSection(signal: AbortSignal, onChange: () => void): HTMLElement {
  const body = el("tbody");
  const message = el("p", { testid: "accounts-message", attrs: { role: "status" } });
  const say = (text: string, error = false) => {
    message.textContent = text;
    message.className = error ? "alert alert--error" : "";
  };
  const report: Report = {
    say,
    fail: (err) => say(err instanceof ApiError ? err.message : String(err), true),
  };
  const load = async () => {
    try {
      const users = await usersApi.list(signal);
      const changed = () => {
        void load(); // a disabled account's row reads so
        onChange();
      };
      body.replaceChildren(
        ...users.map((user) => userRow(user, lastAdminReason(user, users), report, changed)),
      );
    } catch (err) {
      if (!signal.aborted) report.fail(err);
    }
  };
  const form = newUserForm(report, async () => {
    await load();
    onChange();
  });
  void load();
  return el(
    "section",
    { className: "card", testid: "accounts" },
    el("h2", { text: "Accounts" }),
    // Above the table: what an action in a row did is read where the row is.
    message,
    el(
      "table",
      { className: "data-table", testid: "accounts-table" },
      el(
        "thead",
        {},
        el(
          "tr",
          {},
          ...["Name", "Role", "Since", "Status", ""].map((text) =>
            el("th", { text, attrs: { scope: "col" } }),
          ),
        ),
      ),
      body,
    ),
    el("h3", { text: "New account" }),
    form,
  );
}
