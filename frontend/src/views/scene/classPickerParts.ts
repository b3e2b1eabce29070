// Parts of the class picker (classPicker.ts): one line of its list, keeping the active line
// in view, and where the box goes.
import { el } from "../../dom";
import { classText } from "../../state/classNames";
import type { ClassOption } from "./classRanking";

/**
 * The list's line of an option: its key (1-9), name, the class an alias stands for, and a note
 * (the detector's score for the class at the box).
 */
export function optionItem(
  option: ClassOption,
  index: number,
  active: boolean,
  onPick: (name: string) => void,
  note: string | null = null,
): HTMLLIElement {
  return el(
    "li",
    {
      className: active ? "is-active" : "",
      testid: "class-option",
      attrs: {
        role: "option",
        "aria-selected": active,
        "data-name": option.name,
        "data-class": option.cls,
      },
      on: {
        mousedown: (event) => event.preventDefault(), // keep the field's focus
        click: () => onPick(option.name),
      },
    },
    index < 9
      ? el("kbd", { text: String(index + 1) })
      : el("span", { className: "class-picker-pad" }),
    el("span", { text: classText(option.name) }),
    option.name !== option.cls
      ? el("span", {
          className: "class-picker-alias",
          text: `→ ${classText(option.cls)}`,
        })
      : null,
    note ? el("span", { className: "class-picker-note", text: note }) : null,
  );
}

/** Scroll the list so that its line `index` is in view (not scrollIntoView: the page stays). */
export function keepInView(list: HTMLElement, index: number): void {
  const line = list.children[index] as HTMLElement | undefined;
  if (line && line.offsetTop < list.scrollTop) list.scrollTop = line.offsetTop;
  else if (line && line.offsetTop + line.offsetHeight > list.scrollTop + list.clientHeight)
    list.scrollTop = line.offsetTop + line.offsetHeight - list.clientHeight;
}

/** Place the (shown) box beside the rectangle `near` (client pixels), inside the window. */
export function placeBeside(
  box: HTMLElement,
  near: { left: number; top: number; right: number; bottom: number },
): void {
  const width = box.offsetWidth;
  const height = box.offsetHeight;
  const left = near.right + 8 + width <= window.innerWidth ? near.right + 8 : near.left - 8 - width;
  const top = Math.min(window.innerHeight - height - 8, Math.max(8, near.top));
  box.style.left = `${Math.max(8, left) + window.scrollX}px`;
  box.style.top = `${top + window.scrollY}px`;
}
