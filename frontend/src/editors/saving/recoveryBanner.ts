// The save bar's banner for edits a previous visit left unsaved (kept in this browser):
// restore them, or discard them.
import { button, el, formatTime } from "../../dom";
import { plural, type SceneSession } from "../../state/sceneSession";
import { describeEdit } from "../../state/supportGraph";
import { LAYOUT_CHANGE } from "./pendingList";

export interface RecoveryBanner {
  element: HTMLElement;
  update(): void;
}

export function recoveryBanner(session: SceneSession): RecoveryBanner {
  const text = el("span", { testid: "recovery-text" });
  const restore = button("Restore them (Shift+U)", {
    className: "primary",
    testid: "recovery-restore",
    onClick: () => session.restoreRecovered(),
  });
  const element = el(
    "div",
    { className: "alert alert--info", testid: "recovery-banner", attrs: { role: "alert" } },
    text,
    el(
      "div",
      { className: "save-row" },
      restore,
      button("Discard them", {
        testid: "recovery-discard",
        onClick: () => session.dismissRecovered(),
      }),
    ),
  );
  return {
    element,
    update() {
      const recovered = session.recovered;
      element.hidden = !recovered;
      restore.disabled = !session.editable;
      if (!recovered) return;
      const changes = [
        ...recovered.edits.map(describeEdit),
        ...(recovered.layout ? [LAYOUT_CHANGE] : []),
      ];
      text.textContent =
        `${plural(changes.length, "unsaved change")} from your last visit ` +
        `(${formatTime(recovered.savedAt)}, on revision ${recovered.baseRevision}) ` +
        `never reached the server: ${changes.join("; ")}.`;
    },
  };
}
