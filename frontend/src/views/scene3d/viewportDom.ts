// The 3D panel's page furniture: its toolbar (view buttons, export), the canvas and the status
// line over it. Nothing here knows three.js.
import { button, el } from "../../dom";

export type Scene3dStatus = "loading" | "ready" | "missing" | "error" | "no-webgl";

/**
 * What end-to-end tests read from the 3D view (the canvas's `scene3dProbe` property): the
 * scene as drawn, where an object can be clicked, and how many frames were rendered.
 */
export interface Scene3dProbe {
  frames: number;
  /** Milliseconds spent in each of the last frames' render calls (CPU side), newest last. */
  renderMs: number[];
  roomCorners(): number[][] | null;
  cameraPose(): { pitchDeg: number; rollDeg: number } | null;
  frustumShown(): boolean;
  photoOnFrustum(): boolean;
  arrows(): { child: string; parent: string; type: string }[];
  /** A client point where a click hits the object (not hidden by another), or null. */
  screenPointOf(id: string): { x: number; y: number } | null;
  /** The object's colour as drawn now (linear RGB; brighter while selected or hovered). */
  objectColour(id: string): number[] | null;
  /** How long the last scene.glb took to parse and bake into what is drawn (milliseconds),
   * and its triangles; null before the first. */
  glbLoad(): { ms: number; triangles: number } | null;
  /** The last frame's draw calls and triangles, and the drawing buffer's size then. */
  renderInfo(): { calls: number; triangles: number; width: number; height: number };
  /** Turn the view about the orbit target, as a horizontal drag does (radians). */
  orbit(azimuth: number): void;
  /** The depth points drawn (flat x, y, z, world frame), null for a scene without depth;
   * `shown`: whether they are drawn now. */
  depthPoints(): { shown: boolean; partial: number[]; completed: number[] } | null;
}

export type ProbedCanvas = HTMLCanvasElement & { scene3dProbe?: Scene3dProbe };

export interface ViewportDom {
  canvas: ProbedCanvas;
  /** The canvas's box: the renderer follows its size. */
  viewport: HTMLElement;
  overviewButton: HTMLButtonElement;
  photoViewButton: HTMLButtonElement;
  exportButton: HTMLButtonElement;
  /** Where the view's own controls go (the depth points' checkbox), first in the toolbar. */
  extras: HTMLElement;
  /** Says the view's state on the panel and the canvas (data-status) and in the status line. */
  setStatus(state: Scene3dStatus, text: string): void;
  /** The line over the view naming the object pointed at or selected ("": hidden). */
  setCaption(text: string): void;
}

/** Fill `container` with the toolbar, the canvas and its status line. */
export function buildViewportDom(container: HTMLElement): ViewportDom {
  const canvas: ProbedCanvas = el("canvas", {
    testid: "scene3d-canvas",
    attrs: {
      tabindex: 0,
      "aria-label": "3D scene: drag to orbit, scroll to zoom, click to select",
    },
  });
  const status = el("p", { className: "scene3d-status", testid: "scene3d-status" });
  // Enabled once the view can be drawn (see mountScene3d).
  const viewButton = (text: string, testid: string) => button(text, { testid, disabled: true });
  const overviewButton = viewButton("Overview", "scene3d-overview");
  const photoViewButton = viewButton("Photo viewpoint", "scene3d-photo-view");
  const exportButton = viewButton("Export PNG", "scene3d-export");
  const caption = el("p", { className: "scene3d-caption", testid: "scene3d-caption" });
  caption.hidden = true;
  const viewport = el("div", { className: "scene3d-viewport" }, canvas, caption, status);
  const extras = el("span", { className: "toolbar-extras" });
  container.replaceChildren(
    el(
      "div",
      { className: "panel-toolbar" },
      extras,
      el("span", { className: "spacer" }),
      overviewButton,
      photoViewButton,
      exportButton,
    ),
    viewport,
  );
  const setStatus = (state: Scene3dStatus, text: string) => {
    container.dataset.status = state;
    canvas.dataset.status = state;
    status.textContent = text;
    status.hidden = text === "";
  };
  const setCaption = (text: string) => {
    if (caption.textContent !== text) caption.textContent = text;
    caption.hidden = text === "";
  };
  return {
    canvas,
    viewport,
    overviewButton,
    photoViewButton,
    exportButton,
    extras,
    setStatus,
    setCaption,
  };
}
