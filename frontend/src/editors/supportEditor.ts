// The object list: each object's class (a button that opens the class picker) and its
// supporter and support type, editable (read only while the scene is locked). Support edits
// are staged in the session as undoable actions (shown at once on the photo) and autosaved.
import type { SceneObject } from "@holiscene/schema";
import { STRUCTURAL_SUPPORTERS, SUPPORT_TYPES } from "@holiscene/schema";
import { button, el, placeChildren } from "../dom";
import { classText, objectClassText } from "../state/classNames";
import type { SceneSession } from "../state/sceneSession";
import {
  defaultType,
  implausibleBelow,
  isDoubtfulSupport,
  isStructural,
  onlyType,
  type ShownSupport,
  type SupportType,
  typeFor,
  withoutSupporter,
  wouldCycle,
} from "../state/supportGraph";
import { maskColours } from "../views/objectColors";
import { maskStyle } from "../views/photo/maskStyle";
import { rgbCss } from "../views/rgb";
import { boxConfidence } from "./boxConfidence";
import { objectMesh } from "./objectMesh";
import { objectSource } from "./objectSource";
import { nearestFirst } from "./supporterOrder";
import { supportStatus } from "./supportStatus";
import { supportSummary } from "./supportSummary";

const NONE = "";

/** Opens the class picker for an object (by id), beside `anchor` (its class button). */
export type ChangeClass = (id: string, anchor: HTMLElement) => void;

interface Row {
  object: SceneObject;
  /** What the row shows of its object (rowKey): the row is made again when it changes. */
  key: string;
  element: HTMLTableRowElement;
  update(): void;
  /** Mark the row hovered or selected as the session says (all update() does for those). */
  highlight(): void;
  /** List the scene's objects as possible supporters (when they changed). */
  listSupporters(objects: readonly SceneObject[]): void;
}

const rowKey = (o: SceneObject) =>
  JSON.stringify([
    o.id,
    o.class,
    o.source_class,
    o.source,
    o.score,
    o.set_by_person,
    boxConfidence(o)?.text,
  ]);

function supporterOptions(object: SceneObject, objects: readonly SceneObject[]): HTMLElement[] {
  return [
    el("option", { text: "— none —", attrs: { value: NONE } }),
    el(
      "optgroup",
      { attrs: { label: "Room" } },
      ...STRUCTURAL_SUPPORTERS.map((name) => el("option", { text: name, attrs: { value: name } })),
    ),
    el(
      "optgroup",
      { attrs: { label: "Objects, nearest first" } },
      ...nearestFirst(
        object,
        objects.filter((other) => other.id !== object.id && !isStructural(other.class)),
      ).map((other) =>
        el("option", {
          text: `${other.id} · ${classText(other.class)}`,
          attrs: { value: other.id },
        }),
      ),
    ),
  ];
}

/** The object's class: a button opening the picker when classes can be changed here. */
function classCell(object: SceneObject, changeClass: ChangeClass | undefined): HTMLElement {
  const text = objectClassText(object);
  if (!changeClass) return el("span", { className: "object-class", text });
  const cell: HTMLButtonElement = button(text, {
    className: "object-class object-class-button",
    testid: `object-class-${object.id}`,
    title: "Change the class (Shift+C on the photo)",
    attrs: { "aria-label": `Class of ${object.id}: ${text}; change it` },
    onClick: () => changeClass(object.id, cell),
  });
  return cell;
}

function setDisabled(control: HTMLButtonElement | HTMLSelectElement, disabled: boolean): void {
  if (control.disabled !== disabled) control.disabled = disabled;
}

/** Disable the supporters that rest on `id` (a loop), but the one it has (`current`). */
function markLoops(
  supporter: HTMLSelectElement,
  id: string,
  current: string | undefined,
  shown: ReadonlyMap<string, ShownSupport>,
): void {
  for (const option of supporter.querySelectorAll("option")) {
    const candidate = option.value;
    const loops =
      candidate !== NONE && !isStructural(candidate) && wouldCycle(id, candidate, shown);
    const disabled = loops && candidate !== current;
    if (option.disabled !== disabled) option.disabled = disabled;
    const title = disabled ? `${candidate} rests on ${id}` : "";
    if (option.title !== title) option.title = title;
  }
}

/** A choice in the row's menus becomes the session's support edit. */
function editOnChange(
  id: string,
  supporter: HTMLSelectElement,
  type: HTMLSelectElement,
  session: SceneSession,
): void {
  supporter.addEventListener("change", () => {
    const parent = supporter.value;
    if (parent === NONE) {
      session.edit(`remove ${id}'s supporter`, [{ kind: "remove_support", child: id }]);
      return;
    }
    session.edit(`${id} on ${parent}`, [
      { kind: "set_support", child: id, parent, type: typeFor(parent, session.shown().get(id)) },
    ]);
  });
  type.addEventListener("change", () => {
    const current = session.shown().get(id);
    if (!current) return;
    session.edit(`${id}: ${type.value}`, [
      { kind: "set_support", child: id, parent: current.parent, type: type.value as SupportType },
    ]);
  });
}

function objectRow(
  object: SceneObject,
  session: SceneSession,
  changeClass: ChangeClass | undefined,
): Row {
  const id = object.id;
  const cls = classCell(object, changeClass);
  const supporter = el("select", {
    testid: `supporter-select-${id}`,
    attrs: { "aria-label": `Supporter of ${id}` },
  });
  const listSupporters = (objects: readonly SceneObject[]) =>
    supporter.replaceChildren(...supporterOptions(object, objects));
  listSupporters(session.objects);
  const type = el(
    "select",
    { testid: `type-select-${id}`, attrs: { "aria-label": `Support type of ${id}` } },
    ...SUPPORT_TYPES.map((t) => el("option", { text: t, attrs: { value: t } })),
  );
  const status = el("span", { className: "badge", testid: `support-status-${id}` });
  const source = objectSource(object);
  const boxTrust = boxConfidence(object);
  const mesh = objectMesh(object);
  const element = el(
    "tr",
    {
      className: "object-row",
      testid: `object-row-${id}`,
      attrs: { "data-object": id },
      on: {
        mouseenter: () => session.hover(id),
        mouseleave: () => session.hover(null),
        focusin: () => session.select(id),
        // A click on the row's name selects the object: the way to one hidden under another
        // on the photo. (Its menus select it when they take the focus.)
        click: () => session.select(id),
      },
    },
    el(
      "th",
      { attrs: { scope: "row" } },
      el(
        "div",
        { className: "object-name" },
        el("span", {
          className: "swatch",
          testid: `object-swatch-${id}`,
          attrs: { "data-swatch-of": id },
        }),
        el("span", { className: "object-id", text: id }),
        cls,
        source.text &&
          el("span", {
            className: `object-source object-source--${source.kind}`,
            testid: `object-source-${id}`,
            text: source.text,
            attrs: { title: source.title },
          }),
        boxTrust &&
          el("span", {
            className: `object-source box-confidence${boxTrust.doubtful ? " box-confidence--doubtful" : ""}`,
            testid: `box-confidence-${id}`,
            text: boxTrust.text,
            attrs: { title: boxTrust.title },
          }),
        mesh &&
          el("span", {
            className: `object-source object-mesh object-mesh--${mesh.kind}`,
            testid: `object-mesh-${id}`,
            text: mesh.text,
            attrs: { title: mesh.title },
          }),
      ),
      status,
    ),
    el("td", {}, supporter),
    el("td", {}, type),
  );

  editOnChange(id, supporter, type, session);

  const update = () => {
    const shown = session.shown();
    const support = shown.get(id);
    // Written only when they change: the list is updated on every change of the session (a
    // hover too), and each write would make the browser restyle the row.
    // The model's live suggestion, drawn dotted on the photo, is what A accepts: the menus
    // show it too, marked (they showed the stored guess, and A stored another supporter).
    const displayed = session.displayed(id);
    const suggested = displayed?.suggested === true;
    supporter.value = displayed?.parent ?? NONE;
    type.value = displayed?.type ?? defaultType(NONE);
    supporter.classList.toggle("is-suggested", suggested);
    type.classList.toggle("is-suggested", suggested);
    // The narrow menu cuts a long supporter short ("o6 · cou"): the pointer reads it whole.
    const supporterText = supporter.selectedOptions[0]?.text ?? "";
    const menuTitle = suggested
      ? `${supporterText}: the model's suggestion (dotted on the photo), not stored yet; ` +
        `A accepts it, R rejects it${support ? ` (the guess before: ${support.parent})` : ""}`
      : supporterText;
    if (supporter.title !== menuTitle) supporter.title = menuTitle;
    setDisabled(supporter, !session.editable);
    // A part of the room holds up one way only ("floor, behind" names nothing).
    setDisabled(type, !support || !session.editable || onlyType(support.parent) !== null);
    if (cls instanceof HTMLButtonElement) setDisabled(cls, !session.editable);
    markLoops(supporter, id, support?.parent, shown);
    const pending = session.isPending(id);
    const chip = supportStatus(support, suggested && !pending, session.doc.scene.stages ?? []);
    if (status.textContent !== chip.text) status.textContent = chip.text;
    // A guess at under even odds is flagged like a missing supporter: it needs a look; so is a
    // supporter from below that stands beside the object on the photo (set here or there).
    const beside =
      support && implausibleBelow(object, session.object(support.parent), support.type);
    const doubtful = !support || Boolean(beside) || (!pending && isDoubtfulSupport(support));
    const badge = `badge${doubtful ? " badge--warn" : ""}${pending ? " badge--pending" : ""}`;
    if (status.className !== badge) status.className = badge;
    const why = beside || chip.title;
    if (status.title !== why) status.title = why;
    element.classList.toggle("is-unsupported", !support);
    element.classList.toggle("is-pending", pending);
    if (element.dataset.unsupported !== String(!support))
      element.dataset.unsupported = String(!support);
    highlight();
  };
  const highlight = () => {
    element.classList.toggle("is-hovered", session.hovered === id);
    element.classList.toggle("is-selected", session.selected === id);
  };
  return { object, key: rowKey(object), element, update, highlight, listSupporters };
}

function structureRow(object: SceneObject): HTMLTableRowElement {
  return el(
    "tr",
    { className: "object-row is-structure", testid: `object-row-${object.id}` },
    el(
      "th",
      { attrs: { scope: "row" } },
      el("span", { className: "object-id", text: object.id }),
      el("span", { className: "object-class", text: object.class }),
    ),
    el("td", { attrs: { colspan: 2 }, text: "room structure (supports, is not supported)" }),
  );
}

/** An action on objects the server has not confirmed (its label), and news of changes. */
export interface UnconfirmedAction {
  readonly failure: { label: string } | null;
  subscribe(listener: () => void): () => void;
}

export function mountSupportEditor(
  container: HTMLElement,
  session: SceneSession,
  changeClass?: ChangeClass,
  unconfirmed?: UnconfirmedAction,
): () => void {
  const summary = el("p", { className: "editor-summary", testid: "support-summary" });
  const body = el("tbody");
  container.replaceChildren(
    summary,
    el(
      "table",
      { className: "object-table", testid: "object-table" },
      el(
        "thead",
        {},
        el(
          "tr",
          {},
          el("th", { text: "Object", attrs: { scope: "col" } }),
          el("th", { text: "Supported by", attrs: { scope: "col" } }),
          el("th", { text: "Type", attrs: { scope: "col" } }),
        ),
      ),
      body,
    ),
  );

  let rows: Row[] = [];
  let builtFor = "";
  let listedFor = "";
  // Rows of objects shown as before are kept (an object edit makes one row, not all); their
  // supporter menus are listed again when the objects' ids, classes or boxes changed.
  const build = () => {
    const objects = session.objects;
    const key = JSON.stringify(objects.map(rowKey));
    if (key === builtFor) return;
    builtFor = key;
    // Boxes too: the menus list the objects nearest first (supporterOrder.ts).
    const listed = JSON.stringify(objects.map((o) => [o.id, o.class, o.bbox]));
    const relist = listed !== listedFor;
    listedFor = listed;
    const kept = new Map(rows.map((r) => [r.key, r]));
    rows = objects
      .filter((o) => !isStructural(o.class))
      .map((o) => {
        const row = kept.get(rowKey(o));
        if (!row) return objectRow(o, session, changeClass);
        if (relist) row.listSupporters(objects);
        return row;
      });
    const structure = objects.filter((o) => isStructural(o.class)).map(structureRow);
    placeChildren(body, [...rows.map((r) => r.element), ...structure]);
    paintSwatches();
  };
  // The swatches match the masks on the photo (by object or by class).
  const paintSwatches = () => {
    const colours = maskColours(
      session.objects,
      maskStyle.get().colouring,
      session.doc.scene.removed_by_person,
    );
    for (const swatch of body.querySelectorAll<HTMLElement>("[data-swatch-of]")) {
      const colour = colours.get(swatch.dataset.swatchOf ?? "");
      swatch.style.background = colour ? rgbCss(colour) : "";
    }
  };
  const update = () => {
    for (const row of rows) row.update();
    const missing = withoutSupporter(session.objects, session.shown()).length;
    const label = unconfirmed?.failure?.label ?? null;
    const { text, warn } = supportSummary(session.objects, missing, label);
    if (summary.textContent !== text) summary.textContent = text;
    summary.classList.toggle("is-warn", warn);
  };
  // Only scrolls: taking the focus would send the photo's shortcut keys into the select.
  const scrollToSelected = () => {
    const row = rows.find((r) => r.object.id === session.selected);
    if (row && !row.element.contains(document.activeElement)) revealInPanel(row.element);
  };

  build();
  update();
  const stopStyle = maskStyle.subscribe(paintSwatches);
  const unsubscribe = session.subscribe((change) => {
    if (change === "document") build();
    if (change === "select") scrollToSelected();
    // Pointing at an object or choosing one changes no menu or badge: its highlight only
    // (a full update checks every row's menu for loops, for each move onto another object).
    if (change === "hover" || change === "select") for (const row of rows) row.highlight();
    else update();
  });
  const stopFailure = unconfirmed?.subscribe(update);
  return () => {
    stopStyle();
    unsubscribe();
    stopFailure?.();
  };
}

/**
 * Scroll the editor panel (not the page) so that `row` shows below the panel's sticky save
 * bar and inside the window (before the page is scrolled, the panel's foot is below the
 * window's). Where the panel does not scroll by itself (one column: it sits under the photo),
 * the page is left where it is: jumping away from the photo the person just clicked would
 * lose it.
 */
function revealInPanel(row: HTMLElement): void {
  const panel = row.closest<HTMLElement>(".panel--editor");
  if (!panel || panel.scrollHeight <= panel.clientHeight) return;
  const box = panel.getBoundingClientRect();
  const bar = panel.querySelector<HTMLElement>(".save-bar")?.getBoundingClientRect();
  const top = Math.max(box.top, bar?.bottom ?? box.top, 0) + 4;
  const bottom = Math.min(box.bottom, window.innerHeight) - 4;
  const at = row.getBoundingClientRect();
  if (at.top < top) panel.scrollTop -= top - at.top;
  else if (at.bottom > bottom) panel.scrollTop += Math.min(at.bottom - bottom, at.top - top);
}
