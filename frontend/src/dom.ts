// Small helpers for building DOM trees without a framework.

type Child = Node | string | null | undefined | false;
type Listeners = { [K in keyof HTMLElementEventMap]?: (event: HTMLElementEventMap[K]) => void };

export interface ElementProps {
  className?: string;
  /** Rendered as `data-testid`, the handle end-to-end tests use. */
  testid?: string;
  text?: string;
  attrs?: Record<string, string | number | boolean | null | undefined>;
  on?: Listeners;
}

function setAttrs(node: Element, attrs: ElementProps["attrs"]): void {
  for (const [name, value] of Object.entries(attrs ?? {})) {
    if (value === false || value === null || value === undefined) continue;
    node.setAttribute(name, value === true ? "" : String(value));
  }
}

/** Create an HTML element with properties and children. */
export function el<K extends keyof HTMLElementTagNameMap>(
  tag: K,
  props: ElementProps = {},
  ...children: Child[]
): HTMLElementTagNameMap[K] {
  const node = document.createElement(tag);
  if (props.className) node.className = props.className;
  if (props.testid) node.dataset.testid = props.testid;
  if (props.text !== undefined) node.textContent = props.text;
  setAttrs(node, props.attrs);
  for (const [type, listener] of Object.entries(props.on ?? {})) {
    node.addEventListener(type, listener as EventListener);
  }
  for (const child of children) {
    if (child) node.append(child);
  }
  return node;
}

export interface ButtonProps {
  className?: string;
  /** Rendered as `data-testid`. */
  testid?: string;
  title?: string;
  /** "button" unless said otherwise, so a button in a form does not submit it by accident. */
  type?: "button" | "submit";
  disabled?: boolean;
  hidden?: boolean;
  /** Any other attributes (aria-*, data-*). */
  attrs?: ElementProps["attrs"];
  onClick?: (event: MouseEvent) => void;
}

/** A button with its text, title and click handler. */
export function button(text: string, props: ButtonProps = {}): HTMLButtonElement {
  const { type = "button", title, disabled, hidden, attrs, onClick } = props;
  return el("button", {
    className: props.className,
    testid: props.testid,
    text,
    attrs: { type, title, disabled, hidden, ...attrs },
    on: onClick ? { click: onClick } : {},
  });
}

/** A form field: its label text above the input (and any hint after it). */
export function labelledField(
  label: string,
  input: HTMLElement,
  ...after: Child[]
): HTMLLabelElement {
  return el(
    "label",
    { className: "field" },
    el("span", { className: "field-label", text: label }),
    input,
    ...after,
  );
}

/** An error line for a form, hidden until a message is put in it. */
export function hiddenErrorAlert(testid: string): HTMLParagraphElement {
  return el("p", {
    className: "alert alert--error",
    testid,
    attrs: { role: "alert", hidden: true },
  });
}

/** An error line saying why `what` failed, from a caught error. */
export function failureAlert(what: string, error: unknown): HTMLParagraphElement {
  return el("p", {
    className: "alert alert--error",
    text: `${what} failed: ${error instanceof Error ? error.message : String(error)}`,
    attrs: { role: "alert" },
  });
}

const SVG_NS = "http://www.w3.org/2000/svg";

/** Create an SVG element with attributes. */
export function svgEl<K extends keyof SVGElementTagNameMap>(
  tag: K,
  attrs: Record<string, string | number | undefined> = {},
  ...children: (SVGElement | string)[]
): SVGElementTagNameMap[K] {
  const node = document.createElementNS(SVG_NS, tag);
  for (const [name, value] of Object.entries(attrs)) {
    if (value !== undefined) node.setAttribute(name, String(value));
  }
  node.append(...children);
  return node;
}

/**
 * Make `parent`'s children exactly `nodes`, in order, moving only what is out of place: nodes
 * kept from the last redraw stay where they are (an image is not decoded again, a row keeps
 * its focus).
 */
export function placeChildren(parent: Element, nodes: readonly Element[]): void {
  // A control with the keyboard on it, in a node replaced here (a row redrawn after an edit):
  // the keyboard moves to its twin in the new node, not back to the page's start.
  const focused =
    typeof document === "undefined" ? null : (document.activeElement as HTMLElement | null);
  const testid = focused && parent.contains(focused) ? focused.dataset?.testid : undefined;
  let cursor = parent.firstElementChild;
  for (const node of nodes) {
    if (node === cursor) cursor = cursor.nextElementSibling;
    else parent.insertBefore(node, cursor);
  }
  while (cursor) {
    const next = cursor.nextElementSibling;
    cursor.remove();
    cursor = next;
  }
  if (testid && !parent.contains(document.activeElement))
    parent
      .querySelector<HTMLElement>(`[data-testid="${CSS.escape(testid)}"]`)
      ?.focus({ preventScroll: true });
}

/** A score, confidence or probability as a whole percent, rounded down: 99.6% never reads
 * as a sure 100%, and 29.6% is under a 30% threshold as it is. */
export const percentText = (share: number) => `${Math.floor(share * 100 + 1e-9)}%`;

/** A time as every page shows it: the month named (no day/month ambiguity), to the second
 * (revisions can follow each other within a minute). */
const FULL_TIME: Intl.DateTimeFormatOptions = {
  year: "numeric",
  month: "short",
  day: "numeric",
  hour: "numeric",
  minute: "2-digit",
  second: "2-digit",
};

export function formatTime(iso: string, options: Intl.DateTimeFormatOptions = FULL_TIME): string {
  const date = new Date(iso);
  return Number.isNaN(date.getTime()) ? iso : date.toLocaleString(undefined, options);
}

/** A time for a table column: the month named (no day/month ambiguity), to the minute; the
 * year only when it is not this one (the column stays narrow). */
export function formatShortTime(iso: string, now: Date = new Date()): string {
  const date = new Date(iso);
  if (Number.isNaN(date.getTime())) return iso;
  const thisYear = date.getFullYear() === now.getFullYear();
  return formatTime(iso, {
    month: "short",
    day: "numeric",
    ...(thisYear ? {} : { year: "numeric" }),
    hour: "numeric",
    minute: "2-digit",
  });
}
