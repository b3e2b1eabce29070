// The dashboard (#/dashboard): scenes per state, what each person did, and how far two
// annotators agree on the scenes labelled twice; for admins, the accounts.
import type { Dashboard, PersonStats, SceneAgreement } from "@holiscene/schema";
import { SCENE_STATES, stateLabel, workflowApi } from "../../api/workflow";
import { button, el } from "../../dom";
import { hasRole } from "../../state/currentUser";
import "../workflow/workflow.css";
import { everyWhileVisible } from "../common/everyWhileVisible";
import { accountsSection } from "./accounts";

const DASHBOARD_CHECK_MS = 10_000;

const percent = (share: number) => `${(100 * share).toFixed(1)}%`;

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

/** `toAccounts`: the page opens at its accounts (the header's Accounts link). */
export function mountDashboardPage(container: HTMLElement, toAccounts = false): () => void {
  const abort = new AbortController();
  const content = el("div", { className: "dashboard-content" });
  const status = el("p", { testid: "dashboard-status", attrs: { role: "status" } });
  const refreshButton = button("Refresh", { testid: "dashboard-refresh" });
  let shown = "";
  const refresh = async (background = false) => {
    try {
      const dashboard = await workflowApi.dashboard(abort.signal);
      // Checked again in the background: redrawn only when a figure moved.
      const key = JSON.stringify(dashboard);
      if (background && key === shown) return;
      shown = key;
      const mean = dashboard.mean_agreement;
      content.replaceChildren(
        statesSection(dashboard),
        el(
          "section",
          { className: "card" },
          el("h2", { text: "People" }),
          // The state counts above are scenes now; these are steps over time, and say so.
          el("p", {
            className: "field-hint",
            testid: "people-hint",
            text:
              "Annotating: the scenes each person holds now. Submitted, Accepted and Sent " +
              "back: what happened to the scenes they annotated; Reviews done: the scenes " +
              "they accepted or sent back as a reviewer. Every such step so far counts (a " +
              "scene submitted again after a rejection counts twice), so they need not add " +
              "up to the scene counts above.",
          }),
          table(
            "people-table",
            ["Name", "Role", "Annotating", "Submitted", "Accepted", "Sent back", "Reviews done"],
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
      // Opened at the accounts: scrolled there once the figures above them are laid out.
      if (toAccounts && !background) accounts?.scrollIntoView({ block: "start" });
    } catch (err) {
      if (background) return; // the figures shown stay; the next check tries again
      status.hidden = false;
      if (!abort.signal.aborted)
        status.textContent = `Could not load the dashboard: ${err instanceof Error ? err.message : String(err)}`;
    }
  };
  refreshButton.addEventListener("click", () => void refresh());
  const accounts = hasRole("admin") ? accountsSection(abort.signal, () => void refresh()) : null;
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
      accounts,
    ),
  );
  void refresh();
  // Counts move as people work: looked at again while the tab is visible.
  const stopWatching = everyWhileVisible(DASHBOARD_CHECK_MS, () => void refresh(true));
  return () => {
    stopWatching();
    abort.abort();
  };
}
