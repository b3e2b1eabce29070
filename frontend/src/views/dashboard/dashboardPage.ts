// The dashboard (#/dashboard): scenes per state, what each person did, and how far two
// annotators agree on the scenes labelled twice; for admins, the accounts.
import type { Dashboard, PersonStats, SceneAgreement, UserInfo } from "@holiscene/schema";
import { ApiError } from "../../api/errors";
import { type Role, SCENE_STATES, stateLabel, usersApi, workflowApi } from "../../api/workflow";
import { button, el, formatTime, labelledField } from "../../dom";
import { hasRole } from "../../state/currentUser";
import "../workflow/workflow.css";

const ROLES: readonly Role[] = ["annotator", "reviewer", "admin"];
const percent = (share: number) => `${(100 * share).toFixed(1)} %`;

function table(testid: string, headers: string[], numeric: number[], rows: HTMLElement[]) {
  return el(
    "table",
    { className: "data-table", testid },
    el(
      "thead",
      {},
      el(
        "tr",
        {},
        ...headers.map((text, i) =>
          el("th", { text, className: numeric.includes(i) ? "num" : "", attrs: { scope: "col" } }),
        ),
      ),
    ),
    el("tbody", {}, ...rows),
  );
}

const num = (value: number | string, testid?: string) =>
  el("td", { className: "num", text: String(value), testid });

function personRow(person: PersonStats): HTMLElement {
  const id = (what: string) => `person-${person.name}-${what}`;
  return el(
    "tr",
    { testid: `person-${person.name}` },
    el("th", { text: person.name, attrs: { scope: "row" } }),
    el("td", { text: person.role ?? "(no account)" }),
    num(person.in_annotation, id("in_annotation")),
    num(person.submitted, id("submitted")),
    num(person.accepted, id("accepted")),
    num(person.rejected, id("rejected")),
    num(person.reviewed, id("reviewed")),
  );
}

function agreementRow(row: SceneAgreement): HTMLElement {
  return el(
    "tr",
    { testid: `agreement-${row.scene_id}` },
    el(
      "th",
      { attrs: { scope: "row" } },
      el("a", { text: row.name, attrs: { href: `#/scenes/${encodeURIComponent(row.scene_id)}` } }),
    ),
    el("td", { text: row.annotators.join(" / ") }),
    el("td", { text: row.revisions.map((r) => `#${r}`).join(" / ") }),
    num(`${row.matching} / ${row.objects}`),
    num(percent(row.agreement)),
  );
}

function statesSection(dashboard: Dashboard): HTMLElement {
  return el(
    "section",
    { className: "card" },
    el("h2", { text: "Scenes per state" }),
    el(
      "ul",
      { className: "state-counts", testid: "state-counts" },
      ...SCENE_STATES.map((state) =>
        el(
          "li",
          {},
          el("span", {
            className: "state-count",
            text: String(dashboard.states[state] ?? 0),
            testid: `state-count-${state}`,
          }),
          el("span", {
            className: "state-badge",
            text: stateLabel(state),
            attrs: { "data-state": state },
          }),
        ),
      ),
    ),
  );
}

function accountsSection(signal: AbortSignal, onChange: () => void): HTMLElement {
  const body = el("tbody");
  const message = el("p", { testid: "accounts-message", attrs: { role: "status" } });
  const say = (text: string, error = false) => {
    message.textContent = text;
    message.className = error ? "alert alert--error" : "";
  };
  const fail = (err: unknown) => say(err instanceof ApiError ? err.message : String(err), true);

  const userRow = (user: UserInfo) => {
    const role = el(
      "select",
      { testid: `role-select-${user.name}`, attrs: { "aria-label": `Role of ${user.name}` } },
      ...ROLES.map((r) =>
        el("option", { text: r, attrs: { value: r, selected: r === user.role } }),
      ),
    );
    role.addEventListener("change", async () => {
      try {
        await usersApi.setRole(user.name, role.value as Role);
        say(`${user.name} is now ${role.value}.`);
        onChange();
      } catch (err) {
        role.value = user.role;
        fail(err);
      }
    });
    const reset = button("Reset password…", { testid: `reset-password-${user.name}` });
    reset.addEventListener("click", async () => {
      const password = window.prompt(`New password for ${user.name} (at least 10 characters)`);
      if (!password) return;
      try {
        await usersApi.resetPassword(user.name, password);
        say(`New password set for ${user.name}; their sessions ended.`);
      } catch (err) {
        fail(err);
      }
    });
    return el(
      "tr",
      { testid: `account-${user.name}` },
      el("th", { text: user.name, attrs: { scope: "row" } }),
      el("td", {}, role),
      el("td", { text: formatTime(user.created_at) }),
      el("td", {}, reset),
    );
  };

  const name = el("input", {
    testid: "new-user-name",
    attrs: {
      type: "text",
      required: true,
      maxlength: 64,
      autocomplete: "off",
      pattern: "[a-z0-9][a-z0-9_.\\-]*",
    },
  });
  const role = el(
    "select",
    { testid: "new-user-role" },
    ...ROLES.map((r) => el("option", { text: r, attrs: { value: r } })),
  );
  const password = el("input", {
    testid: "new-user-password",
    attrs: { type: "password", required: true, minlength: 10, autocomplete: "new-password" },
  });
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
  );
  const load = async () => {
    try {
      const users = await usersApi.list(signal);
      body.replaceChildren(...users.map(userRow));
    } catch (err) {
      if (!signal.aborted) fail(err);
    }
  };
  form.addEventListener("submit", async (event) => {
    event.preventDefault();
    create.disabled = true;
    try {
      const user = await usersApi.create({
        name: name.value.trim(),
        role: role.value as Role,
        password: password.value,
      });
      form.reset();
      say(`Added ${user.name} (${user.role}).`);
      await load();
      onChange();
    } catch (err) {
      fail(err);
    } finally {
      create.disabled = false;
    }
  });
  void load();
  return el(
    "section",
    { className: "card", testid: "accounts" },
    el("h2", { text: "Accounts" }),
    el(
      "table",
      { className: "data-table", testid: "accounts-table" },
      el(
        "thead",
        {},
        el(
          "tr",
          {},
          ...["Name", "Role", "Since", ""].map((text) =>
            el("th", { text, attrs: { scope: "col" } }),
          ),
        ),
      ),
      body,
    ),
    el("h3", { text: "New account" }),
    form,
    message,
  );
}

export function mountDashboardPage(container: HTMLElement): () => void {
  const abort = new AbortController();
  const content = el("div", { className: "dashboard-content" });
  const status = el("p", { testid: "dashboard-status", attrs: { role: "status" } });
  const refreshButton = button("Refresh", { testid: "dashboard-refresh" });
  const refresh = async () => {
    try {
      const dashboard = await workflowApi.dashboard(abort.signal);
      const mean = dashboard.mean_agreement;
      content.replaceChildren(
        statesSection(dashboard),
        el(
          "section",
          { className: "card" },
          el("h2", { text: "People" }),
          table(
            "people-table",
            ["Name", "Role", "Annotating", "Submitted", "Accepted", "Rejected", "Reviewed"],
            [2, 3, 4, 5, 6],
            dashboard.people.map(personRow),
          ),
        ),
        el(
          "section",
          { className: "card" },
          el("h2", { text: "Agreement between annotators" }),
          el("p", {
            testid: "mean-agreement",
            text:
              mean === null
                ? "No scene was labelled twice yet (a reviewer can ask for a second annotation of a submitted or accepted scene)."
                : `Mean agreement ${percent(mean)} over ${dashboard.agreement.length} scene(s): share of objects with the same supporter and support type in both annotations.`,
          }),
          dashboard.agreement.length > 0
            ? table(
                "agreement-table",
                ["Scene", "Annotators", "Revisions", "Same supporter and type", "Agreement"],
                [3, 4],
                dashboard.agreement.map(agreementRow),
              )
            : null,
        ),
      );
      status.textContent = "";
      status.hidden = true;
    } catch (err) {
      status.hidden = false;
      if (!abort.signal.aborted)
        status.textContent = `Could not load the dashboard: ${err instanceof Error ? err.message : String(err)}`;
    }
  };
  refreshButton.addEventListener("click", () => void refresh());
  container.replaceChildren(
    el(
      "div",
      { className: "dashboard-page", testid: "dashboard" },
      el(
        "div",
        { className: "card-header" },
        el("h1", { text: "Dashboard" }),
        el("span", { className: "spacer" }),
        refreshButton,
      ),
      status,
      content,
      hasRole("admin") ? accountsSection(abort.signal, () => void refresh()) : null,
    ),
  );
  void refresh();
  return () => abort.abort();
}
