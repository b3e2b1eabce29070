// The class picker: a small box near the pointer with a search field and the matching classes
// (classRanking.ts): the classes the detector saw at the box first (classHints.ts, with its
// score), then the most used. Typing filters; ↑/↓ move; Enter or a click picks;
// 1-9 pick the n-th line (class names have no digits); Esc or a click elsewhere cancels.
// With nothing typed nothing is highlighted until ↑/↓: Enter on a blank field would otherwise
// save the first line, often a faint detector guess, without the person choosing it.
// Picks are counted in this browser (with the scene's own objects) to order the list.
import type { SceneObject } from "@holiscene/schema";
import { el, percentText } from "../../dom";
import type { LikelyClass } from "./classHints";
import { keepInView, optionItem, placeBeside } from "./classPickerParts";
import { CLASS_OPTIONS, type ClassOption, rankClasses } from "./classRanking";
import "./classPicker.css";

const USES_KEY = "holiscene.classUses";

function storedUses(): Record<string, number> {
  try {
    const value: unknown = JSON.parse(localStorage.getItem(USES_KEY) ?? "{}");
    return value && typeof value === "object" ? (value as Record<string, number>) : {};
  } catch {
    return {};
  }
}

/** Remember a pick (for the order of the list next time). */
export function countPick(cls: string): void {
  const uses = storedUses();
  uses[cls] = (uses[cls] ?? 0) + 1;
  try {
    localStorage.setItem(USES_KEY, JSON.stringify(uses));
  } catch {
    // Storage may be unavailable: the order then follows this scene only.
  }
}

/** Uses per NYU-40 class: objects of the scene and picks in this browser. */
export function classUses(objects: readonly SceneObject[]): Map<string, number> {
  const uses = new Map(Object.entries(storedUses()).filter(([, n]) => typeof n === "number"));
  for (const object of objects) uses.set(object.class, (uses.get(object.class) ?? 0) + 1);
  return uses;
}

export interface PickerOptions {
  /** Where to show it (client pixels): beside this rectangle. */
  near: { left: number; top: number; right: number; bottom: number };
  title: string;
  objects: readonly SceneObject[];
  /** The class now (listed first when nothing is typed). */
  current?: string;
  /** Classes the detector saw at the box, most likely first (listed next, with their score). */
  likely?: readonly LikelyClass[];
}

let closeOpen: (() => void) | null = null;

const NONE = -1;
const HINT = "↑↓ move · Enter or 1–9 pick · Esc cancel";

/** Close the picker if one is open, as cancelled (its page is going). */
export function cancelClassPicker(): void {
  closeOpen?.();
}

/** Open the picker; resolves to the name picked (a class or an alias), or null if cancelled. */
export function pickClass(options: PickerOptions): Promise<string | null> {
  closeOpen?.(); // one at a time: the one open is cancelled
  const uses = classUses(options.objects);
  const input = el("input", {
    className: "class-picker-input",
    testid: "class-picker-input",
    attrs: {
      type: "text",
      placeholder: "Type a class…",
      "aria-label": "Class",
      autocomplete: "off",
      spellcheck: false,
      role: "combobox",
      "aria-expanded": true,
      "aria-controls": "class-picker-list",
    },
  });
  const list = el("ul", {
    className: "class-picker-list",
    testid: "class-picker-list",
    attrs: { role: "listbox", id: "class-picker-list" },
  });
  const hint = el("p", { className: "class-picker-hint", testid: "class-picker-hint", text: HINT });
  const box = el(
    "div",
    {
      className: "class-picker",
      testid: "class-picker",
      attrs: { role: "dialog", "aria-label": options.title },
    },
    el("strong", { className: "class-picker-title", text: options.title }),
    input,
    list,
    hint,
  );
  let shown: ClassOption[] = [];
  let active = NONE; // the highlighted line; NONE until something is typed or ↑/↓ pressed
  const likely = options.likely ?? [];
  const detectorNote = (cls: string) => {
    const hint = likely.find((l) => l.cls === cls);
    return hint ? `detector ${percentText(hint.score)}` : null;
  };

  const draw = () => {
    shown = rankClasses(
      input.value,
      uses,
      12,
      likely.map((l) => l.cls),
    );
    if (!input.value.trim() && options.current) {
      const current = options.current;
      shown = [
        ...shown.filter((o) => o.name === current),
        ...shown.filter((o) => o.name !== current),
      ];
    }
    active = Math.min(active, shown.length - 1);
    list.replaceChildren(
      ...shown.map((option, i) =>
        optionItem(option, i, i === active, finish, detectorNote(option.cls)),
      ),
    );
    if (shown.length === 0) {
      list.append(
        el("li", { className: "class-picker-none", text: `No class matches "${input.value}"` }),
      );
    }
    keepInView(list, active);
  };

  let resolve: (value: string | null) => void = () => {};
  const done = new Promise<string | null>((r) => {
    resolve = r;
  });
  const onOutside = (event: PointerEvent) => {
    if (!box.contains(event.target as Node)) finish(null);
  };
  // Where the keyboard was: it goes back there when the picker closes by a key (removing
  // the focused input would drop it to the page's start, far from the object).
  const before = document.activeElement;
  const finish = (name: string | null) => {
    if (closeOpen === cancel) closeOpen = null;
    window.removeEventListener("pointerdown", onOutside, true);
    const hadFocus = box.contains(document.activeElement);
    box.remove();
    if (hadFocus && before instanceof HTMLElement && before !== document.body && before.isConnected)
      before.focus({ preventScroll: true });
    if (name) countPick(CLASS_OPTIONS.find((o) => o.name === name)?.cls ?? name);
    resolve(name);
  };

  const cancel = () => finish(null);
  closeOpen = cancel;

  input.addEventListener("input", () => {
    active = input.value.trim() ? 0 : NONE;
    hint.textContent = HINT;
    draw();
  });
  input.addEventListener("keydown", (event) => {
    if (event.key === "ArrowDown" || event.key === "ArrowUp") {
      const step = event.key === "ArrowDown" ? 1 : -1;
      const from = active === NONE ? (step > 0 ? -1 : 0) : active;
      active = (from + step + shown.length) % Math.max(1, shown.length);
      draw();
    } else if (event.key === "Enter") {
      const option = shown[active];
      if (option) finish(option.name);
      else hint.textContent = "Type a class, or pick a line: ↑↓ then Enter, or 1–9";
    } else if (event.key === "Escape") {
      finish(null);
    } else if (/^[1-9]$/.test(event.key) && !event.ctrlKey && !event.altKey) {
      const option = shown[Number(event.key) - 1];
      if (option) finish(option.name);
    } else return;
    event.preventDefault();
    event.stopPropagation();
  });

  document.body.append(box);
  draw();
  placeBeside(box, options.near);
  input.focus({ preventScroll: true });
  window.addEventListener("pointerdown", onOutside, true);
  return done;
}
