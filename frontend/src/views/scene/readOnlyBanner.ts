// The banner of a scene that cannot be edited now (submitted, accepted, or the server said so).
import { el } from "../../dom";
import { plural, type SceneSession } from "../../state/sceneSession";

/** The server's reason as a sentence: capital first, one full stop. */
const sentence = (text: string) =>
  `${text.charAt(0).toUpperCase()}${text.slice(1).replace(/\.?\s*$/, ".")}`;

/**
 * The banner of a scene that cannot be edited now (submitted, accepted, or the server said
 * so): why, what is off, and that unsaved changes are kept.
 */
export function readOnlyBanner(session: SceneSession): {
  element: HTMLElement;
  dispose: () => void;
} {
  const reason = el("strong", { testid: "read-only-reason" });
  const detail = el("span", { testid: "read-only-detail" });
  const element = el(
    "div",
    {
      className: "alert alert--info read-only-banner",
      testid: "read-only-banner",
      attrs: { role: "status", hidden: true },
    },
    reason,
    " ",
    detail,
  );
  const update = () => {
    const lock = session.lock;
    element.hidden = lock === null;
    reason.textContent = lock?.title ?? "";
    const kept = session.unsavedCount;
    // Short: the banner stands between a reviewer and the photo they came to judge; what
    // still works is in its tooltip.
    element.title =
      "Editing (supports, objects, room) and its keys are off; the photo, the 3D view and ? " +
      "still work.";
    detail.textContent =
      (lock?.reason ? sentence(lock.reason) : "") +
      (kept > 0
        ? ` Your ${plural(kept, "unsaved change")} ${kept === 1 ? "is" : "are"} kept in this browser until the scene can be edited again.`
        : "");
  };
  update();
  return {
    element,
    dispose: session.subscribe((change) => {
      if (change === "lock" || change === "edits" || change === "document") update();
    }),
  };
}
