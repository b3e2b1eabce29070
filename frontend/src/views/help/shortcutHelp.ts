// The keyboard help overlay: "?" lists every shortcut registered at that moment, grouped by
// scope, so the list is always what the keys actually do on this page; keys that do nothing
// now (editing keys on a read-only scene, conflict keys without a conflict) are greyed.
import { button, el } from "../../dom";
import { listShortcuts, registerShortcut, type Shortcut } from "../../shortcuts";
import "./shortcutHelp.css";

function keyLabel(keys: string): HTMLElement {
  return el(
    "span",
    { className: "shortcut-keys" },
    ...keys.split(/\+(?!$)/).flatMap((part, i) => [i > 0 ? "+" : null, el("kbd", { text: part })]),
  );
}

function row(shortcut: Shortcut): HTMLElement {
  return el(
    "tr",
    {
      className: shortcut.enabled ? "" : "is-off",
      testid: "shortcut-row",
      attrs: {
        "data-keys": shortcut.keys.join(" "),
        "data-enabled": String(shortcut.enabled),
        title: shortcut.enabled ? null : "Not available now",
      },
    },
    el(
      "td",
      { className: "shortcut-key-cell" },
      ...shortcut.keys.flatMap((k, i) => [i > 0 ? " or " : null, keyLabel(k)]),
    ),
    el("td", { text: shortcut.description }),
  );
}

/** Mount the overlay (hidden) and its "?" key; returns the function that removes both. */
export function mountShortcutHelp(host: HTMLElement): () => void {
  const body = el("div", { className: "shortcut-help-body" });
  const close = button("Close", {
    className: "shortcut-help-close",
    testid: "shortcut-help-close",
  });
  const overlay = el(
    "div",
    {
      className: "shortcut-help",
      testid: "shortcut-help",
      attrs: {
        role: "dialog",
        "aria-modal": "true",
        "aria-label": "Keyboard shortcuts",
        hidden: true,
      },
    },
    el(
      "div",
      { className: "shortcut-help-panel" },
      el(
        "div",
        { className: "shortcut-help-header" },
        el("h2", { text: "Keyboard shortcuts" }),
        close,
      ),
      body,
    ),
  );
  host.append(overlay);
  let removeEscape: (() => void) | null = null;

  const hide = () => {
    overlay.hidden = true;
    removeEscape?.();
    removeEscape = null;
  };
  const show = () => {
    const groups = new Map<string, Shortcut[]>();
    for (const s of listShortcuts()) groups.set(s.scope, [...(groups.get(s.scope) ?? []), s]);
    body.replaceChildren(
      ...[...groups].map(([scope, shortcuts]) =>
        el(
          "section",
          { className: "shortcut-group", attrs: { "data-scope": scope } },
          el("h3", { text: scope }),
          el("table", {}, el("tbody", {}, ...shortcuts.map(row))),
        ),
      ),
    );
    overlay.hidden = false;
    close.focus({ preventScroll: true });
    removeEscape ??= registerShortcut({
      keys: "Escape",
      description: "Close this list",
      scope: "Keyboard help",
      run: hide,
    });
  };

  close.addEventListener("click", hide);
  overlay.addEventListener("click", (event) => {
    if (event.target === overlay) hide();
  });
  const removeHelpKey = registerShortcut({
    keys: "?",
    description: "Show or hide the keyboard shortcuts",
    scope: "General",
    run: () => (overlay.hidden ? show() : hide()),
  });
  return () => {
    hide();
    removeHelpKey();
    overlay.remove();
  };
}
