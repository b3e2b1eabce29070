// Tools on the photo: a toolbar of tools (each with a one-key shortcut; Esc goes back to
// Select) and the routing of pointer presses on the photo, in image pixels, to the active
// tool. "Select" is the photo's own behaviour (hover, click, dragging arrows): it handles
// nothing here, so those listeners get the events. Any other tool gets the primary button's
// presses and the clicks are kept from the photo's own listeners. Other modules add tools
// with `tools.add(tool)` (the box tool, the mask tools), drawing in `host.overlay`.
import type { SceneObject } from "@holiscene/schema";
import { button, el, svgEl } from "../dom";
import { registerShortcut } from "../shortcuts";
import { lockText, titleUnlessLocked } from "../state/editLock";
import type { ObjectEditor } from "../state/objectEditor";
import type { SceneSession } from "../state/sceneSession";
import { objectName } from "./boxes/boxEdits";
import { changeSelectedClass, removeSelected, SET_CLASS_KEY } from "./objectShortcuts";
import { routePointer, type ToolState } from "./tools/pointerRouting";
import "./photoTools.css";

/** A point in image pixels (x right, y down from the photo's top-left corner). */
export type ImagePoint = [number, number];

export interface PhotoTool {
  /** Unique on the page: "select", "box", "brush", ... */
  id: string;
  /** The toolbar button's text. */
  label: string;
  /** Its one-key shortcut (must be free on the scene page: see the help overlay, "?"). */
  key: string;
  /** What it does, for the button's title and the shortcut help. */
  description: string;
  /** CSS cursor over the photo while active. */
  cursor?: string;
  /** Whether it changes the scene (off while the scene is read only). */
  edits?: boolean;
  /** Whether it draws on the selected object (a mask tool): while one is selected, hovering
   *  others does not highlight them, which would dim the mask being drawn. */
  drawsOnSelected?: boolean;
  down?(at: ImagePoint, event: PointerEvent): void;
  /** Every pointer move over the photo while active (pressed or not: e.g. a brush outline). */
  move?(at: ImagePoint, event: PointerEvent): void;
  up?(at: ImagePoint, event: PointerEvent): void;
  /** Drop whatever is half drawn (Esc, or another tool chosen). */
  cancel?(): void;
  /** Whether something is half drawn: Esc drops it first (cancel), the next Esc goes to Select. */
  drafting?(): boolean;
  /** Told when it becomes the active tool. */
  activate?(): void;
  /** Controls shown beside the toolbar while it is active (a brush size, ...). */
  options?(): HTMLElement | null;
}

export interface PhotoToolHost {
  svg: SVGSVGElement;
  /** A layer above masks, arrows and labels, for the tools' drawings. */
  overlay: SVGGElement;
  session: SceneSession;
  objects: ObjectEditor;
  /** The photo's size in pixels. */
  width: number;
  height: number;
  /** The pointer in image pixels. */
  toImage(event: MouseEvent): ImagePoint | null;
  /** The object whose mask is under the pointer. */
  objectAt(event: MouseEvent): string | null;
  /** Image pixels per screen pixel now (changes with zoom): handles and lines scale by it. */
  pixelSize(): number;
  /** Told after the photo was zoomed or panned (redraw what is sized by pixelSize). */
  onView(listener: () => void): () => void;
}

export interface PhotoTools {
  readonly host: PhotoToolHost;
  /** Add a tool (a button and its key); returns the function that removes it. */
  add(tool: PhotoTool): () => void;
  activate(id: string): void;
  readonly active: PhotoTool;
  /** Told when the active tool changes. */
  onChange(listener: (tool: PhotoTool) => void): () => void;
  dispose(): void;
}

export const SELECT_TOOL_KEY = "V";
export const SELECT_TOOL_ID = "select";
const SCOPE = "Photo tools";

/** A tool button's tooltip: what it does, and its key. */
const toolTitle = (tool: PhotoTool) => `${tool.description} (${tool.key})`;

/** A tool's one-line hint under the toolbar (what a press on the photo does). */
export function toolHint(text: string): HTMLElement {
  return el("span", { className: "tool-hint", text });
}

/** What Select's hint says while an object is selected on an editable scene: what can be done
 * with it, the removal and the class as links (a mouse user found no other way to remove an
 * object than the Delete key, which only the help named). */
function selectedObjectHint(host: PhotoToolHost, object: SceneObject): HTMLElement {
  const link = (text: string, testid: string, title: string, run: () => void) =>
    button(text, { className: "link-like tool-hint-link", testid, title, onClick: run });
  return el(
    "span",
    { className: "tool-hint", testid: "selected-object-hint" },
    `${objectName(object)}: `,
    link(
      "remove",
      "remove-selected-object",
      `Remove ${object.id} with its mask and supports (Delete; Ctrl+Z brings it back)`,
      () => void removeSelected(host.objects),
    ),
    ` (Delete) · `,
    link(
      "change class",
      "change-selected-class",
      `Pick another class for ${object.id} (${SET_CLASS_KEY})`,
      () => void changeSelectedClass(host.objects, host.svg),
    ),
    ` (${SET_CLASS_KEY}) · drag its arrow's head to a new supporter.`,
  );
}

/** Select: the photo's own clicks and arrow drags (see the module's comment). */
function selectTool(host: PhotoToolHost): PhotoTool {
  const { session } = host;
  return {
    id: SELECT_TOOL_ID,
    label: "Select",
    key: SELECT_TOOL_KEY,
    description: "Select: click objects and arrows, drag arrows to a new supporter",
    options: () => {
      // An armed pick (an arrow clicked, or S) is said here, in the row that stays in view:
      // the next click on an object changes a label.
      const picking = session.editable ? session.picking : null;
      // Why a key or a click did nothing ("The floor holds o0 up from below only.") is said
      // here too: the line under the photo that says it may be below the window.
      const said = picking ? null : session.message;
      const selected = session.editable ? session.selectedObject : undefined;
      if (!picking && said === null && selected) return selectedObjectHint(host, selected);
      const hint = toolHint(
        picking
          ? `Now click the object that holds up ${picking} (or F, W, C; or drag its arrow onto the floor or a wall) · Esc cancels.`
          : (said ??
              (session.editable
                ? "Click an object or an arrow to select it; drag an arrow's head to a new supporter."
                : "Click an object or an arrow to select it and see where its labels came from.")),
      );
      hint.classList.toggle("is-picking", picking !== null || said !== null);
      return hint;
    },
  };
}

/** The toolbar goes into `toolbar`; pointer events of `host.svg` go to the active tool. */
export function mountPhotoTools(toolbar: HTMLElement, host: PhotoToolHost): PhotoTools {
  const tools: PhotoTool[] = [];
  const buttons = new Map<string, HTMLButtonElement>();
  const removers = new Map<string, () => void>();
  const listeners = new Set<(tool: PhotoTool) => void>();
  const buttonRow = el("span", {
    className: "photo-tools",
    attrs: { role: "toolbar", "aria-label": "Photo tools" },
  });
  const select = selectTool(host);
  const optionsBox = el("span", { className: "photo-tool-options", testid: "photo-tool-options" });
  toolbar.append(buttonRow, optionsBox);
  // The options take the height of the tallest tool's options at this width: changing tool
  // (a key while the pointer is on the photo) must not move the photo under the pointer.
  let measuredWidth = -1;
  const reserveOptionsHeight = () => {
    measuredWidth = optionsBox.getBoundingClientRect().width;
    optionsBox.style.minHeight = "";
    let tallest = 0;
    // A scene the person can only look at keeps Select: no room for the others' options.
    for (const tool of host.session.viewOnly ? [select] : tools) {
      optionsBox.replaceChildren(...[tool.options?.() ?? null].filter((n) => n !== null));
      tallest = Math.max(tallest, optionsBox.getBoundingClientRect().height);
    }
    optionsBox.style.minHeight = tallest > 0 ? `${Math.ceil(tallest)}px` : "";
    show();
  };
  // Tools are added one after another while the page mounts: one measure after the last.
  let measureQueued = false;
  const queueMeasure = () => {
    if (measureQueued) return;
    measureQueued = true;
    queueMicrotask(() => {
      measureQueued = false;
      reserveOptionsHeight();
    });
  };
  const resizing =
    typeof ResizeObserver === "undefined"
      ? null
      : new ResizeObserver(() => {
          if (optionsBox.getBoundingClientRect().width !== measuredWidth) queueMeasure();
        });
  resizing?.observe(optionsBox);
  const state: ToolState = { active: select, pressed: null };

  const usable = (tool: PhotoTool) => !tool.edits || host.session.editable;

  const show = () => {
    for (const [id, button] of buttons) {
      const tool = tools.find((t) => t.id === id);
      button.setAttribute("aria-pressed", String(id === state.active.id));
      button.classList.toggle("is-active", id === state.active.id);
      button.disabled = tool ? !usable(tool) : true;
      if (tool)
        button.title = titleUnlessLocked(toolTitle(tool), tool.edits ? host.session.lock : null);
    }
    host.svg.dataset.tool = state.active.id;
    host.svg.style.cursor = state.active.cursor ?? "";
    optionsBox.replaceChildren(...[state.active.options?.() ?? null].filter((n) => n !== null));
  };

  // The editing tool a lock took away: given back when the scene is editable again, unless
  // the person chose a tool meanwhile (a colleague's save can lock the page for a moment).
  let takenByLock: PhotoTool | null = null;

  const activate = (id: string) => {
    takenByLock = null;
    const next = tools.find((t) => t.id === id);
    if (!next || !usable(next)) return;
    if (next !== state.active) {
      state.active.cancel?.();
      state.pressed = null;
      state.active = next;
      next.activate?.();
    }
    show();
    for (const listener of listeners) listener(state.active);
  };

  const add = (tool: PhotoTool): (() => void) => {
    if (tools.some((t) => t.id === tool.id)) throw new Error(`a photo tool "${tool.id}" exists`);
    tools.push(tool);
    const toolButton = button(tool.label, {
      testid: `photo-tool-${tool.id}`,
      title: toolTitle(tool),
      attrs: { "aria-pressed": "false" },
      onClick: () => activate(tool.id),
    });
    buttons.set(tool.id, toolButton);
    buttonRow.append(toolButton);
    const removeKey = registerShortcut({
      keys: tool.key,
      description: tool.description,
      scope: SCOPE,
      run: () => activate(tool.id),
      enabled: () => usable(tool),
      whenOff: () => {
        const lock = host.session.lock;
        if (lock) host.session.say(`${tool.label}: ${lockText(lock)}`);
      },
    });
    const remove = () => {
      removeKey();
      toolButton.remove();
      buttons.delete(tool.id);
      removers.delete(tool.id);
      const index = tools.indexOf(tool);
      if (index >= 0) tools.splice(index, 1);
      if (state.active === tool) activate(select.id);
    };
    removers.set(tool.id, remove);
    show();
    queueMeasure();
    return remove;
  };

  // One signal takes every listener off again in dispose().
  const listening = new AbortController();
  routePointer(host, state, select, listening.signal);

  add(select);
  const escapeSpec = {
    keys: "Escape",
    description: "Drop what the photo tool has half drawn, else go back to Select",
    scope: SCOPE,
    run: () => (state.active.drafting?.() ? state.active.cancel?.() : activate(select.id)),
    enabled: () => state.active !== select,
  };
  let removeEscape = registerShortcut(escapeSpec);
  // The newest enabled registration of a key wins: taking a tool registers Escape again, so
  // it beats the page's "clear the selection" (mounted later) while a tool is in use.
  listeners.add((tool) => {
    if (tool === select) return;
    removeEscape();
    removeEscape = registerShortcut(escapeSpec);
  });
  // A scene turning read only drops the editing tools; turning editable gives the dropped one
  // back.
  const unsubscribe = host.session.subscribe((change) => {
    // Select's hint says when a pick is armed, and why an action did nothing.
    if ((change === "select" || change === "message") && state.active === select) show();
    if (change !== "lock") return;
    queueMeasure(); // the room the options keep depends on which tools can be used
    const taken = takenByLock;
    if (!usable(state.active)) {
      const active = state.active;
      activate(select.id);
      takenByLock = active;
    } else if (taken && state.active === select && tools.includes(taken) && usable(taken)) {
      activate(taken.id);
    } else show();
  });

  return {
    host,
    add,
    activate,
    get active() {
      return state.active;
    },
    onChange(listener) {
      listeners.add(listener);
      return () => listeners.delete(listener);
    },
    dispose() {
      state.active.cancel?.();
      unsubscribe();
      removeEscape();
      for (const remove of [...removers.values()]) remove();
      listening.abort();
      resizing?.disconnect();
      buttonRow.remove();
      optionsBox.remove();
    },
  };
}

/** The overlay layer tools draw in (above everything else on the photo). */
export function toolOverlay(): SVGGElement {
  return svgEl("g", { class: "tool-overlay", "data-testid": "tool-overlay" });
}
