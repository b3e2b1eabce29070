// The save bar's list of unsaved changes: each support edit, and the room layout's.
import { el } from "../../dom";
import type { SceneSession } from "../../state/sceneSession";
import { describeEdit } from "../../state/supportGraph";

/** The room layout's line in the lists of unsaved changes. */
export const LAYOUT_CHANGE = "room layout changed (corners or camera height)";

export interface PendingList {
  element: HTMLElement;
  update(): void;
}

export function pendingList(session: SceneSession): PendingList {
  const items = el("ul");
  const heading = el("strong", { text: "Unsaved changes" });
  const element = el("div", { className: "pending-list", testid: "pending-edits" }, heading, items);
  return {
    element,
    update() {
      element.hidden = session.unsavedCount === 0;
      // The list scrolls past a few lines: the heading says how many there are.
      heading.textContent = `Unsaved changes (${session.unsavedCount})`;
      items.replaceChildren(
        ...session.pending.map((edit) =>
          el("li", { text: describeEdit(edit), attrs: { "data-child": edit.child } }),
        ),
        ...(session.layoutPending
          ? [el("li", { text: LAYOUT_CHANGE, attrs: { "data-layout": "" } })]
          : []),
      );
    },
  };
}
