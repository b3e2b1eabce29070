// Rendering on demand: a frame is drawn only when something asked for one (orbit, resize,
// hover, layout change), which keeps software WebGL cheap. On software WebGL the view moves at
// half resolution (a quarter of the pixels to shade) and is drawn sharp again once it has been
// still for a while.
import * as THREE from "three";
import type { OrbitControls } from "three/examples/jsm/controls/OrbitControls.js";
import { isSoftwareWebGL } from "./softwareGl";

/** The view counts as moving until this long after its last change (milliseconds), or three
 * frame times when frames are slower: a slow machine would otherwise switch every frame. */
const MOVING_MS = 200;
/** Render times kept for the probe. */
const KEPT_FRAME_TIMES = 240;

/** A WebGL renderer on the canvas, or null when the browser has no WebGL. */
export function createRenderer(canvas: HTMLCanvasElement): THREE.WebGLRenderer | null {
  try {
    // preserveDrawingBuffer lets tests and "Export PNG" read the pixels after a frame.
    return new THREE.WebGLRenderer({
      canvas,
      antialias: !isSoftwareWebGL(),
      preserveDrawingBuffer: true,
    });
  } catch {
    return null;
  }
}

/** Frames drawn so far and their cost, for the end-to-end probe. */
export interface FrameStats {
  frames: number;
  renderMs: number[];
}

export interface ViewportRenderInputs {
  renderer: THREE.WebGLRenderer;
  scene: THREE.Scene;
  camera: THREE.PerspectiveCamera;
  controls: OrbitControls;
  canvas: HTMLCanvasElement;
  /** The element whose size the drawing follows. */
  viewport: HTMLElement;
  stats: FrameStats;
  /** Called after each frame (the labels over the view follow it). */
  afterFrame?: () => void;
}

export class ViewportRender {
  private frame = 0;
  private lastFrameAt = 0;
  private frameInterval = 0; // between the last two frames, milliseconds
  private still = 0;
  private readonly observer: ResizeObserver;
  /** The drawing buffer's size at the last frame. */
  lastFrameSize = { width: 0, height: 0 };

  constructor(private readonly inputs: ViewportRenderInputs) {
    const fullRatio = Math.min(window.devicePixelRatio, 2);
    const movingRatio = isSoftwareWebGL() ? fullRatio / 2 : fullRatio;
    inputs.renderer.setPixelRatio(fullRatio);
    inputs.controls.addEventListener("change", () => {
      this.setRatio(movingRatio);
      clearTimeout(this.still);
      const wait = Math.max(MOVING_MS, Math.min(3 * this.frameInterval, 2000));
      this.still = window.setTimeout(() => this.setRatio(fullRatio), wait);
      this.requestRender();
    });
    this.observer = new ResizeObserver(this.resize);
    this.observer.observe(inputs.viewport);
  }

  /** Draw a frame now. */
  readonly render = (): void => {
    const { renderer, scene, camera, canvas, stats } = this.inputs;
    this.frame = 0;
    const start = performance.now();
    this.frameInterval = start - this.lastFrameAt;
    this.lastFrameAt = start;
    renderer.render(scene, camera);
    this.inputs.afterFrame?.();
    this.lastFrameSize = { width: canvas.width, height: canvas.height };
    stats.frames += 1;
    stats.renderMs.push(performance.now() - start);
    if (stats.renderMs.length > KEPT_FRAME_TIMES) {
      stats.renderMs.splice(0, stats.renderMs.length - KEPT_FRAME_TIMES);
    }
  };

  /** Draw a frame at the next animation frame (once, however often it is asked). */
  readonly requestRender = (): void => {
    this.frame ||= requestAnimationFrame(this.render);
  };

  /** Fit the drawing buffer and the camera's aspect to the viewport's size. */
  readonly resize = (): void => {
    const { renderer, camera, viewport } = this.inputs;
    const { clientWidth: width, clientHeight: height } = viewport;
    if (width === 0 || height === 0) return;
    renderer.setSize(width, height, false);
    camera.aspect = width / height;
    camera.updateProjectionMatrix();
    this.requestRender();
  };

  private setRatio(ratio: number): void {
    if (this.inputs.renderer.getPixelRatio() === ratio) return;
    this.inputs.renderer.setPixelRatio(ratio);
    this.resize();
  }

  dispose(): void {
    this.observer.disconnect();
    cancelAnimationFrame(this.frame);
    clearTimeout(this.still);
  }
}
