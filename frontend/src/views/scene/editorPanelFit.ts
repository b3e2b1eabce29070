// The editor panel sticks beside the photo and scrolls by itself. Until the page is scrolled
// its top is lower than where it sticks, so a height of the whole window put its foot (and a
// row selected on the photo, scrolled to the panel's foot) below the window. The panel is
// kept to the part of the window below its top; it grows to the window as the page scrolls.
const MARGIN_PX = 8; // as the panel's sticky top (0.5rem)
const LEAST_PX = 240; // a short window still shows a few rows

/** Keep `panel` inside the window while it is sticky; returns the function that stops. */
export function fitPanelToWindow(panel: HTMLElement): () => void {
  let frame = 0;
  const fitNow = () => {
    frame = 0;
    // One column (a narrow window): the panel does not stick and takes its whole height.
    if (getComputedStyle(panel).position !== "sticky") {
      panel.style.maxHeight = "";
      return;
    }
    const top = Math.max(panel.getBoundingClientRect().top, MARGIN_PX);
    panel.style.maxHeight = `${Math.max(window.innerHeight - top - MARGIN_PX, LEAST_PX)}px`;
  };
  const queue = () => {
    if (!frame) frame = requestAnimationFrame(fitNow);
  };
  window.addEventListener("scroll", queue, { passive: true });
  window.addEventListener("resize", queue);
  // The warnings opened or closed above it move its top too.
  const layout = typeof ResizeObserver === "undefined" ? null : new ResizeObserver(queue);
  if (panel.parentElement) layout?.observe(panel.parentElement);
  fitNow();
  return () => {
    layout?.disconnect();
    cancelAnimationFrame(frame);
    window.removeEventListener("scroll", queue);
    window.removeEventListener("resize", queue);
  };
}
