// What the object editor is doing: saving an action and what the last one did (e.g. that it
// was applied on top of someone else's revision, or that a new object's mask is its whole
// box) on the dark band over the photo's top edge, the width of the photo, where it moves
// nothing as messages come and go (beside the tool buttons it had 200 pixels and cut the
// part that said what to do); and, in the tool row, an action that could not be saved, kept
// with Retry and Discard until the person chooses.
import { button, el } from "../dom";
import type { ObjectEditor } from "../state/objectEditor";
import { screenRect } from "./boxes/boxEdits";
import { changeClass } from "./objectShortcuts";

/** How long the line says what an action did; only a plain "…: saved." goes (a note with
 * something to do, a mask left as a box, stays until the next action). */
const DONE_MESSAGE_MS = 8000;
const DONE_ONLY = /: saved\.$/;

/** Send the failed action again; an object it added without its class (a box left while its
 * class was picked) is selected and its class asked at once. */
async function retry(editor: ObjectEditor, svg: SVGSVGElement): Promise<void> {
  if (!(await editor.retry())) return;
  const unnamed = editor.takeObjectToName();
  if (!unnamed) return;
  editor.session.select(unnamed.id);
  await changeClass(editor, unnamed, screenRect(svg, unnamed.bbox));
}

export function mountObjectEditBar(
  container: HTMLElement,
  photoBox: HTMLElement,
  svg: SVGSVGElement,
  editor: ObjectEditor,
): () => void {
  const status = el("span", {
    className: "object-edit-status",
    testid: "object-edit-status",
    attrs: { role: "status", "aria-live": "polite" },
  });
  // A long message shows whole on a click (and in its tooltip); the next one is one line again.
  status.addEventListener("click", () => status.classList.toggle("is-expanded"));
  const failureText = el("span", { testid: "object-edit-failure-text" });
  const failure = el(
    "span",
    {
      className: "alert alert--conflict object-edit-failure",
      testid: "object-edit-failure",
      attrs: { role: "alert" },
    },
    failureText,
    button("Retry", {
      className: "primary",
      testid: "object-edit-retry",
      onClick: () => void retry(editor, svg),
    }),
    button("Discard", {
      testid: "object-edit-discard",
      title: "Drop this change",
      onClick: () => editor.discardFailed(),
    }),
  );
  const bar = el("div", { className: "object-edit-bar", testid: "object-edit-bar" }, failure);
  container.append(bar);
  photoBox.append(status);

  // What an action did ("Add d1 (bag): saved.") goes after a while: left up, it reads as news
  // beside later actions of other tools. Errors stay until the next action.
  let fading = 0;
  const update = () => {
    const state = editor.status;
    window.clearTimeout(fading);
    status.textContent = state.kind === "busy" ? `Saving: ${state.label}…` : (state.message ?? "");
    if (state.kind === "idle" && !state.error && DONE_ONLY.test(status.textContent)) {
      const shown = status.textContent;
      fading = window.setTimeout(() => {
        if (status.textContent === shown) status.textContent = status.title = "";
      }, DONE_MESSAGE_MS);
    }
    if (status.title !== status.textContent) status.classList.remove("is-expanded");
    status.title = status.textContent;
    status.classList.toggle("is-error", state.kind === "idle" && state.error);
    status.dataset.state = state.kind;
    const failed = editor.failure;
    failure.hidden = failed === null;
    bar.hidden = failed === null;
    const again = failed?.retrying ? " Trying again every few seconds." : "";
    failureText.textContent = failed
      ? `Not saved: ${failed.label}. ${failed.message}${again} `
      : "";
  };
  update();
  const unsubscribe = editor.subscribe(update);
  return () => {
    window.clearTimeout(fading);
    unsubscribe();
    bar.remove();
    status.remove();
  };
}
