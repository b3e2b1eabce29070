// While the room layout is edited on the photo, the 3D view comes up in a corner of the window
// when its own place under the photo is out of view: the photo and the room it gives are
// never on screen together otherwise, and people dragging a corner could not watch the walls
// follow. It goes back when editing ends, when its place scrolls into view, or when closed.
import { button, el } from "../../dom";
import type { LayoutDraft } from "../../state/layoutDraft";
import "./scene3dInset.css";

/** How much of the 3D panel's place must be in view for the view to stay there. */
const IN_VIEW_SHARE = 0.4;
/** The page's one-column width (styles.css): no editor column beside the photo to cover. */
const ONE_COLUMN = "(max-width: 960px)";

/** Where the view was dragged to (its right and bottom gaps, pixels), for the next editing. */
let placed: { right: number; bottom: number } | null = null;

/**
 * Dragging `handle` moves `box` within the window while it is fixed in the corner: `place(true)`
 * puts it where it was dragged to, `place(false)` back in the page's flow (no offsets).
 */
function movableBy(
  handle: HTMLElement,
  box: HTMLElement,
): { place: (inCorner: boolean) => void; stop: () => void } {
  const place = (inCorner: boolean) => {
    box.style.right = inCorner && placed ? `${placed.right}px` : "";
    box.style.bottom = inCorner && placed ? `${placed.bottom}px` : "";
  };
  const apply = () => place(true);
  const onDown = (down: PointerEvent) => {
    if ((down.target as Element).closest("button")) return; // its ×
    down.preventDefault();
    const start = box.getBoundingClientRect();
    const move = (event: PointerEvent) => {
      const dx = event.clientX - down.clientX;
      const dy = event.clientY - down.clientY;
      const right = window.innerWidth - start.right - dx;
      const bottom = window.innerHeight - start.bottom - dy;
      placed = {
        right: Math.min(Math.max(0, right), window.innerWidth - start.width),
        bottom: Math.min(Math.max(0, bottom), window.innerHeight - start.height),
      };
      apply();
    };
    const up = () => {
      window.removeEventListener("pointermove", move);
      window.removeEventListener("pointerup", up);
    };
    window.addEventListener("pointermove", move);
    window.addEventListener("pointerup", up);
  };
  handle.addEventListener("pointerdown", onDown);
  return {
    place,
    stop: () => {
      handle.removeEventListener("pointerdown", onDown);
      place(false);
    },
  };
}

/**
 * `panel` is the 3D scene's panel; its `.scene3d-viewport` (the canvas and what is drawn over
 * it) is what goes to the corner. Returns the function that stops it.
 */
export function mountScene3dInset(panel: HTMLElement, draft: LayoutDraft): () => void {
  const viewport = panel.querySelector<HTMLElement>(".scene3d-viewport");
  if (!viewport) return () => {};
  let placeInView = false;
  let closed = false;
  // One line at 380 px; the longer word in its tooltip.
  const title = el("span", {
    text: "3D room · drag this bar to move it",
    attrs: { title: "The room follows the corners you drag on the photo" },
  });
  const close = button("×", {
    className: "scene3d-inset-close",
    testid: "scene3d-inset-close",
    title: "Put the 3D view back in its place under the photo",
    onClick: () => {
      closed = true;
      update();
    },
  });
  const bar = el(
    "div",
    { className: "scene3d-inset-bar", testid: "scene3d-inset-bar" },
    title,
    close,
  );
  viewport.prepend(bar);
  const moving = movableBy(bar, viewport);

  const update = () => {
    const inset =
      draft.editing && !closed && !placeInView && !window.matchMedia(ONE_COLUMN).matches;
    if (inset === panel.classList.contains("is-inset")) return;
    // The panel keeps its height while the view is away, so the page does not move under the
    // pointer and the place can be watched coming into view.
    panel.style.minHeight = inset ? `${panel.offsetHeight}px` : "";
    panel.classList.toggle("is-inset", inset);
    moving.place(inset);
  };

  const observer = new IntersectionObserver(
    ([entry]) => {
      placeInView = (entry?.intersectionRatio ?? 0) >= IN_VIEW_SHARE;
      update();
    },
    { threshold: [0, IN_VIEW_SHARE, 1] },
  );
  observer.observe(panel);
  const stopDraft = draft.subscribe((change) => {
    if (change !== "mode") return;
    closed = false; // each editing starts with the view in reach again
    update();
  });
  return () => {
    moving.stop();
    observer.disconnect();
    stopDraft();
    bar.remove();
    panel.classList.remove("is-inset");
    panel.style.minHeight = "";
  };
}
