// The list page: the upload form and every scene, newest first, with its workflow state
// (filterable) and "Next scene" for annotators.
import type { SceneSummary } from "@holiscene/schema";
import { api } from "../../api/client";
import { isFinished } from "../../api/jobs";
import {
  SCENE_STATES,
  type SceneState,
  stateBadge,
  stateLabel,
  workflowApi,
} from "../../api/workflow";
import { button, el, formatShortTime, formatTime } from "../../dom";
import { tabStorage } from "../../state/browserStorage";
import { getCurrentUser } from "../../state/currentUser";
import { describeJob, jobColumnText } from "../common/jobProgress";
import { nextSceneControl } from "../workflow/nextScene";
import "../workflow/workflow.css";
import { datasetImportForm } from "./datasetImport";
import { MINE, myWork, sentBack, sentBackText } from "./myWork";
import { SceneSelection } from "./sceneSelection";
import { uploadForm } from "./uploadForm";

/** Where this tab keeps the state filter's value. */
const FILTER_KEY = "holiscene.sceneListFilter";

/** The state filter's value for the archived scenes (not a workflow state). */
const ARCHIVED = "archived";

const REFRESH_WHILE_RUNNING_MS = 2000;
const REFRESH_IDLE_MS = 10_000;
// Header columns that give way in a narrow window (.narrow-hidden in styles.css; their cells in
// sceneRow carry the class too).
const NARROW_HIDDEN = new Set(["Size", "Revision"]);

function sceneRow(scene: SceneSummary, selection: SceneSelection): HTMLTableRowElement {
  const href = `#/scenes/${encodeURIComponent(scene.id)}`;
  const job = scene.latest_job;
  const updated = scene.last_activity_at ?? scene.updated_at;
  const badge = stateBadge(scene.state, scene.archived_at != null);
  return el(
    "tr",
    { testid: `scene-row-${scene.id}` },
    el("td", { className: "select-cell" }, selection.checkbox(scene.id, scene.name)),
    el(
      "td",
      { className: "thumb-cell" },
      el("img", {
        className: "thumb",
        attrs: { src: api.imageUrl(scene.id), alt: "", loading: "lazy", width: 96 },
      }),
    ),
    el(
      "th",
      { attrs: { scope: "row" } },
      el("a", {
        className: "scene-name-link",
        text: scene.name,
        attrs: { href, title: scene.name },
      }),
    ),
    el(
      "td",
      {},
      el("span", {
        className: "state-badge",
        text: badge.text,
        testid: `scene-state-${scene.id}`,
        attrs: {
          "data-state": badge.key,
          title: scene.archived_by ? `Archived by ${scene.archived_by}` : "",
        },
      }),
    ),
    el("td", { text: scene.assignee ?? "—", testid: `scene-assignee-${scene.id}` }),
    el("td", {
      className: "num",
      text: scene.uncertainty === null ? "—" : scene.uncertainty.toFixed(2),
      attrs: {
        title:
          "How unsure the pipeline is: the mean doubt of its supporters (1 - confidence), " +
          "raised by each pipeline warning",
      },
    }),
    el("td", { className: "narrow-hidden", text: `${scene.width}×${scene.height}` }),
    el("td", { text: String(scene.object_count) }),
    el("td", { className: "narrow-hidden", text: String(scene.revision) }),
    el("td", {
      className: "scene-updated",
      text: formatShortTime(updated),
      testid: `scene-updated-${scene.id}`,
      attrs: {
        title: `${formatTime(updated)}: its latest revision or workflow step (taken, submitted, accepted...)`,
      },
    }),
    el("td", {
      className: job?.status === "failed" ? "is-failed" : "",
      // Short in the column (it is the last, cut first on a narrow screen); whole on hover.
      text: job ? jobColumnText(job) : "—",
      attrs: { title: job ? describeJob(job) : undefined },
    }),
  );
}

/** A button that brings `form` into view and puts the keyboard on its first field. */
function jumpTo(text: string, testid: string, form: HTMLFormElement): HTMLButtonElement {
  return button(`${text} ↓`, {
    className: "link-like",
    testid,
    title: `Go to the ${text} form below the list`,
    onClick: () => {
      form.scrollIntoView({ block: "start", behavior: "smooth" });
      form.querySelector<HTMLElement>("input, select, button")?.focus({ preventScroll: true });
    },
  });
}

export function mountSceneList(container: HTMLElement): () => void {
  const abort = new AbortController();
  const body = el("tbody");
  const selection = new SceneSelection();
  const status = el("p", { className: "list-status", testid: "scene-list-status" });
  const table = el(
    "table",
    { className: "scene-table", testid: "scene-list" },
    el(
      "thead",
      {},
      el(
        "tr",
        {},
        el("th", { className: "select-cell", attrs: { scope: "col" } }, selection.allBox),
        ...[
          "",
          "Scene",
          "State",
          "Annotator",
          "Uncertainty",
          "Size",
          "Objects",
          "Revision",
          "Updated",
          "Pipeline",
        ].map((text) =>
          el("th", {
            text,
            className: NARROW_HIDDEN.has(text) ? "narrow-hidden" : "",
            attrs: { scope: "col" },
          }),
        ),
      ),
    ),
    body,
  );
  const filter = el(
    "select",
    { testid: "state-filter", attrs: { "aria-label": "Show scenes in state" } },
    el("option", { text: "All states", attrs: { value: "" } }),
    el("option", {
      text: "Mine to do",
      attrs: { value: MINE, title: "Scenes you annotate, those sent back to you first" },
    }),
    ...SCENE_STATES.map((state) =>
      el("option", { text: stateLabel(state), attrs: { value: state } }),
    ),
    el("option", {
      text: "Archived",
      attrs: { value: ARCHIVED, title: "Scenes an admin archived: out of the other lists" },
    }),
  );
  const next = nextSceneControl({ take: "N", review: "R" });
  // Scenes a reviewer sent back wait on their annotator: said above the list, whatever its
  // order, with the way to them ("Mine to do" lists them first).
  const sentBackLine = el("span", { testid: "sent-back-text" });
  const showMine = button("Show mine to do", {
    className: "link-button",
    testid: "show-sent-back",
    onClick: () => {
      filter.value = MINE;
      filter.dispatchEvent(new Event("change"));
    },
  });
  const sentBackNotice = el(
    "p",
    { className: "sent-back-notice", testid: "sent-back-notice", attrs: { role: "status" } },
    sentBackLine,
    " ",
    showMine,
  );
  sentBackNotice.hidden = true;
  let timer = 0;
  let shown = "";
  // `background`: the timed refresh (faster while a job runs), which is not activity
  // (api/client.ts). Others take, submit and review scenes meanwhile: the list follows.
  const refresh = async (background = false) => {
    clearTimeout(timer);
    if (background && document.visibilityState !== "visible") {
      timer = window.setTimeout(() => void refresh(true), REFRESH_IDLE_MS);
      return;
    }
    try {
      const mine = filter.value === MINE;
      const archived = filter.value === ARCHIVED;
      const state = (mine || archived ? null : filter.value || null) as SceneState | null;
      const scope = archived ? "only" : "exclude";
      const listed = await workflowApi.listScenes(state, abort.signal, background, scope);
      const me = getCurrentUser()?.name ?? null;
      const scenes = mine ? myWork(listed, me) : listed;
      // Known only when the list holds every state (a state filter lists one).
      const back = state === null ? sentBack(listed, me) : [];
      sentBackNotice.hidden = back.length === 0;
      sentBackLine.textContent = sentBackText(back);
      showMine.hidden = mine;
      const now = JSON.stringify(scenes);
      // Unchanged rows are left alone: a checkbox or link under the pointer stays put.
      if (now !== shown) body.replaceChildren(...scenes.map((scene) => sceneRow(scene, selection)));
      shown = now;
      selection.listed(scenes.map((scene) => scene.id));
      table.hidden = scenes.length === 0;
      status.textContent =
        scenes.length > 0
          ? ""
          : mine
            ? `Nothing to do: no scene is yours to annotate or fix. "Next scene" hands you one.`
            : archived
              ? "No scene is archived."
              : state
                ? `No scene is ${stateLabel(state)}.`
                : "No scenes yet: import a photo below.";
      const running = scenes.some((s) => s.latest_job && !isFinished(s.latest_job));
      const wait = running ? REFRESH_WHILE_RUNNING_MS : REFRESH_IDLE_MS;
      timer = window.setTimeout(() => void refresh(true), wait);
    } catch (error) {
      if (!abort.signal.aborted) status.textContent = `Could not load scenes: ${String(error)}`;
    }
  };
  const upload = uploadForm(abort.signal, () => refresh());
  const datasetImport = datasetImportForm(abort.signal, () => refresh());
  container.replaceChildren(
    el(
      "div",
      { className: "list-page" },
      // The scenes first: the work a returning annotator or reviewer came for (below the two
      // import forms it started under the fold at 1280x800); new photos and datasets after.
      el(
        "section",
        { className: "card" },
        el(
          "div",
          { className: "card-header" },
          el("h2", { text: "Scenes" }),
          // The import forms are under the list, which runs long: one click away from its top.
          el(
            "span",
            { className: "list-jumps" },
            jumpTo("New scene", "jump-new-scene", upload),
            jumpTo("Import a dataset", "jump-dataset-import", datasetImport),
          ),
        ),
        el(
          "div",
          { className: "list-filters" },
          el("label", { className: "field-inline" }, "State ", filter),
          next.element,
          selection.element,
        ),
        sentBackNotice,
        status,
        el("div", { className: "table-scroll" }, table),
      ),
      upload,
      datasetImport,
    ),
  );
  // Back from a scene opened from a filtered list (the archived ones, say) finds the list as
  // it was left: the filter is kept for this tab and this person (another who logs in on the
  // tab starts from all states).
  const filterKey = `${FILTER_KEY}.${getCurrentUser()?.name ?? ""}`;
  const kept = tabStorage()?.getItem(filterKey);
  if (kept && [...filter.options].some((o) => o.value === kept)) filter.value = kept;
  filter.addEventListener("change", () => {
    tabStorage()?.setItem(filterKey, filter.value);
    void refresh();
  });
  void refresh();
  return () => {
    abort.abort();
    clearTimeout(timer);
    next.dispose();
  };
}
