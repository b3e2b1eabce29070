// The 3D panel: scene.glb in three.js with the room, the photo's camera frustum (the photo on
// its image plane) and the support arrows; first seen from above and behind the camera,
// orbitable. The room and the frustum follow the layout editor live. Clicking an object
// selects it here and on the photo (the session's selection). It renders on demand (orbit,
// resize, hover, layout change), which keeps software WebGL cheap.
import type { Camera, SceneDocument } from "@holiscene/schema";
import * as THREE from "three";
import { OrbitControls } from "three/examples/jsm/controls/OrbitControls.js";
import { api } from "../../api/client";
import { button, el } from "../../dom";
import { type LayoutDraft, storedRoom } from "../../state/layoutDraft";
import type { SceneSession } from "../../state/sceneSession";
import { maskColours } from "../objectColors";
import { maskStyle } from "../photo/maskStyle";
import { planArrows } from "./arrowPlan";
import { PhotoFrustum } from "./photoFrustum";
import { downloadCanvasPng, pngFileName } from "./pngExport";
import { RoomMesh } from "./roomMesh";
import { isRoomSurface, SceneModel } from "./sceneModel";
import { isSoftwareWebGL } from "./softwareGl";
import { SupportArrows3d } from "./supportArrows3d";

type Status = "loading" | "ready" | "missing" | "error" | "no-webgl";

/** Distance of the frustum's image plane from the camera centre, metres. */
const FRUSTUM_DEPTH = 0.6;
/** The view counts as moving until this long after its last change (milliseconds), or three
 * frame times when frames are slower: a slow machine would otherwise switch every frame. */
const MOVING_MS = 200;
/** A press that moves less than this (pixels) before release is a click, not an orbit. */
const CLICK_SLOP = 5;

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
  /** The last frame's draw calls and triangles, and the drawing buffer's size then. */
  renderInfo(): { calls: number; triangles: number; width: number; height: number };
  /** Turn the view about the orbit target, as a horizontal drag does (radians). */
  orbit(azimuth: number): void;
}

export type ProbedCanvas = HTMLCanvasElement & { scene3dProbe?: Scene3dProbe };

/** The photo camera's vertical field of view in degrees (55 when K is unknown). */
function verticalFov(camera: Camera | null | undefined, imageHeight: number): number {
  const fy = camera?.K[1][1];
  return fy ? THREE.MathUtils.radToDeg(2 * Math.atan(imageHeight / 2 / fy)) : 55;
}

function createRenderer(canvas: HTMLCanvasElement): THREE.WebGLRenderer | null {
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

/** What the GLB depends on: the stages that made the revision (edits keep them). */
const glbKey = (doc: SceneDocument) => JSON.stringify(doc.scene.stages ?? []);

export function mountScene3d(
  container: HTMLElement,
  session: SceneSession,
  layout: LayoutDraft | null = null,
): () => void {
  const canvas: ProbedCanvas = el("canvas", {
    testid: "scene3d-canvas",
    attrs: {
      tabindex: 0,
      "aria-label": "3D scene: drag to orbit, scroll to zoom, click to select",
    },
  });
  const status = el("p", { className: "scene3d-status", testid: "scene3d-status" });
  const viewButton = (text: string, testid: string) => button(text, { testid, disabled: true });
  const overviewButton = viewButton("Overview", "scene3d-overview");
  const photoViewButton = viewButton("Photo viewpoint", "scene3d-photo-view");
  const exportButton = viewButton("Export PNG", "scene3d-export");
  const viewport = el("div", { className: "scene3d-viewport" }, canvas, status);
  container.replaceChildren(
    el(
      "div",
      { className: "panel-toolbar" },
      el("span", { className: "hint", text: "Drag to orbit, right-drag to pan, scroll to zoom" }),
      el("span", { className: "spacer" }),
      overviewButton,
      photoViewButton,
      exportButton,
    ),
    viewport,
  );
  const setStatus = (state: Status, text: string) => {
    container.dataset.status = state;
    canvas.dataset.status = state;
    status.textContent = text;
    status.hidden = text === "";
  };

  const renderer = createRenderer(canvas);
  if (!renderer) {
    setStatus("no-webgl", "The 3D view needs WebGL, which this browser does not provide.");
    return () => {};
  }
  renderer.setPixelRatio(Math.min(window.devicePixelRatio, 2));
  const scene = new THREE.Scene();
  scene.background = new THREE.Color(0xe8ecf1);
  // No lights: objects and arrows are lit once, when baked (bakedMesh.ts), the room is flat.

  const room = new RoomMesh();
  const arrows = new SupportArrows3d();
  scene.add(room.root, arrows.root);
  let frustum: PhotoFrustum | null = null;
  let frustumK = "";

  const { image, camera: photoCamera } = session.doc.scene;
  const camera = new THREE.PerspectiveCamera(verticalFov(photoCamera, image.height), 1, 0.05, 200);
  const controls = new OrbitControls(camera, canvas);
  controls.enableDamping = false;

  const probe: Scene3dProbe = {
    frames: 0,
    renderMs: [],
    roomCorners: () => (room.room ? room.corners() : null),
    cameraPose: () => (frustum ? frustum.pitchRoll : null),
    frustumShown: () => frustum !== null && frustum.root.parent === scene,
    photoOnFrustum: () => frustum?.hasPhoto ?? false,
    arrows: () => arrows.arrows.map(({ child, parent, type }) => ({ child, parent, type })),
    screenPointOf: (id) => screenPointOf(id),
    objectColour: (id) => model?.colourOf(id)?.toArray() ?? null,
    orbit: (azimuth) => {
      const offset = camera.position.clone().sub(controls.target);
      offset.applyAxisAngle(new THREE.Vector3(0, 1, 0), azimuth);
      camera.position.copy(controls.target).add(offset);
      controls.update(); // its "change" event asks for a frame
    },
    renderInfo: () => ({
      calls: renderer.info.render.calls,
      triangles: renderer.info.render.triangles,
      ...lastFrameSize,
    }),
  };
  canvas.scene3dProbe = probe;

  let frame = 0;
  let lastFrameSize = { width: 0, height: 0 };
  let lastFrameAt = 0;
  let frameInterval = 0; // between the last two frames, milliseconds
  const render = () => {
    frame = 0;
    const start = performance.now();
    frameInterval = start - lastFrameAt;
    lastFrameAt = start;
    renderer.render(scene, camera);
    lastFrameSize = { width: canvas.width, height: canvas.height };
    probe.frames += 1;
    probe.renderMs.push(performance.now() - start);
    if (probe.renderMs.length > 240) probe.renderMs.splice(0, probe.renderMs.length - 240);
  };
  const requestRender = () => {
    frame ||= requestAnimationFrame(render);
  };
  // On software WebGL the view moves at half resolution (a quarter of the pixels to shade)
  // and is drawn sharp again once it has been still for a while (MOVING_MS).
  const fullRatio = Math.min(window.devicePixelRatio, 2);
  const movingRatio = isSoftwareWebGL() ? fullRatio / 2 : fullRatio;
  let still = 0;
  const setRatio = (ratio: number) => {
    if (renderer.getPixelRatio() === ratio) return;
    renderer.setPixelRatio(ratio);
    resize();
  };
  controls.addEventListener("change", () => {
    setRatio(movingRatio);
    clearTimeout(still);
    const wait = Math.max(MOVING_MS, Math.min(3 * frameInterval, 2000));
    still = window.setTimeout(() => setRatio(fullRatio), wait);
    requestRender();
  });

  const resize = () => {
    const { clientWidth: width, clientHeight: height } = viewport;
    if (width === 0 || height === 0) return;
    renderer.setSize(width, height, false);
    camera.aspect = width / height;
    camera.updateProjectionMatrix();
    requestRender();
  };
  const observer = new ResizeObserver(resize);
  observer.observe(viewport);

  let model: SceneModel | null = null;
  let loadedGlb = "";
  let focus = new THREE.Sphere(new THREE.Vector3(3, 0, 0), 2);

  /** The room, frustum and arrows for the current revision and layout draft. */
  const showLive = () => {
    const doc = session.doc;
    const live = layout ? layout.live : storedRoom(doc);
    room.set(live?.room ?? null);
    room.setEditing(layout?.editing ?? false);
    model?.setRoomVisible(live === null);
    const K = doc.scene.camera?.K;
    const key = JSON.stringify(K ?? null);
    if (key !== frustumK) {
      frustumK = key;
      if (frustum) {
        scene.remove(frustum.root);
        frustum.dispose();
        frustum = null;
      }
      if (K) {
        const { width, height } = doc.scene.image;
        frustum = new PhotoFrustum(K, width, height, FRUSTUM_DEPTH);
        frustum.loadPhoto(api.imageUrl(session.sceneId), requestRender);
        scene.add(frustum.root);
      }
    }
    // Without pitch and roll the frustum is drawn level (as the reviewer viewer does).
    frustum?.setPose(live?.pitchDeg ?? 0, live?.rollDeg ?? 0);
    const floorY = doc.scene.camera?.height_m != null ? -doc.scene.camera.height_m : null;
    arrows.set(
      planArrows(session.objects, session.shown().values(), {
        corners: live?.corners3d ?? null,
        floorY,
      }),
    );
    requestRender();
  };

  const fitFocus = () => {
    const bounds = model?.objectBounds() ?? new THREE.Box3();
    if (bounds.isEmpty() && room.room) {
      for (const corner of room.corners()) bounds.expandByPoint(new THREE.Vector3(...corner));
    }
    if (!bounds.isEmpty()) focus = bounds.getBoundingSphere(new THREE.Sphere());
  };

  /** Look at the objects from above and behind the photo's camera, all in view. */
  const overview = () => {
    const centre = focus.center;
    const back = new THREE.Vector3(-centre.x, 0, -centre.z);
    if (back.lengthSq() < 1e-6) back.set(-1, 0, 0);
    const elevation = THREE.MathUtils.degToRad(35);
    const direction = back
      .normalize()
      .multiplyScalar(Math.cos(elevation))
      .setY(Math.sin(elevation));
    const vertical = THREE.MathUtils.degToRad(camera.fov);
    const horizontal = 2 * Math.atan(Math.tan(vertical / 2) * camera.aspect);
    const distance = (focus.radius / Math.sin(Math.min(vertical, horizontal) / 2)) * 1.05;
    camera.position.copy(centre).addScaledVector(direction, distance);
    controls.target.copy(centre);
    controls.update();
    requestRender();
  };

  /** Stand at the photo's camera (the origin), looking down by its pitch. */
  const photoView = () => {
    const pitch = THREE.MathUtils.degToRad(frustum?.pitchRoll.pitchDeg ?? 0);
    const distance = Math.max(1, focus.center.length());
    camera.position.set(0, 0, 0);
    controls.target.set(distance * Math.cos(pitch), -distance * Math.sin(pitch), 0);
    controls.update();
    requestRender();
  };
  overviewButton.addEventListener("click", overview);
  photoViewButton.addEventListener("click", photoView);
  exportButton.addEventListener("click", () => {
    const name = pngFileName(session.doc.scene.name, session.doc.revision);
    downloadCanvasPng(canvas, name, render).catch((error: unknown) => {
      setStatus("error", `Export failed: ${String(error)}`);
    });
  });

  const abort = new AbortController();
  const load = async () => {
    const doc = session.doc;
    loadedGlb = glbKey(doc);
    if (!model) setStatus("loading", "Loading the 3D scene…");
    const response = await fetch(api.glbUrl(session.sceneId, doc.revision), {
      signal: abort.signal,
    });
    if (response.status === 404) {
      setStatus("missing", "No 3D objects yet: they appear once the pipeline has run.");
      fitFocus();
      overview();
      return;
    }
    if (!response.ok) throw new Error(`scene.glb: ${response.status} ${response.statusText}`);
    const loaded = await SceneModel.parse(await response.arrayBuffer(), session.objects, colours());
    if (abort.signal.aborted) {
      loaded.dispose();
      return;
    }
    const first = model === null;
    if (model) {
      scene.remove(model.view);
      model.dispose();
    }
    model = loaded;
    scene.add(model.view);
    canvas.dataset.revision = String(doc.revision);
    showLive();
    highlight();
    fitFocus();
    resize();
    if (first) overview();
    render();
    setStatus("ready", "");
  };
  const loadSafely = () =>
    load().catch((error: unknown) => {
      if (abort.signal.aborted) return;
      setStatus("error", `The 3D scene could not be shown: ${String(error)}`);
    });
  for (const button of [overviewButton, photoViewButton, exportButton]) button.disabled = false;
  showLive();
  void loadSafely();

  // Hover and click in 3D pick objects, like on the photo.
  const raycaster = new THREE.Raycaster();
  const objectAt = (clientX: number, clientY: number): string | null => {
    if (!model) return null;
    const rect = canvas.getBoundingClientRect();
    const ndc = new THREE.Vector2(
      ((clientX - rect.left) / rect.width) * 2 - 1,
      -((clientY - rect.top) / rect.height) * 2 + 1,
    );
    camera.updateMatrixWorld(); // moved by the controls since the last frame, maybe
    raycaster.setFromCamera(ndc, camera);
    for (const hit of raycaster.intersectObject(model.root, true)) {
      if (!hit.object.visible) continue;
      const id: unknown = hit.object.userData.objectId;
      if (typeof id === "string" && !isRoomSurface(id)) return id;
    }
    return null;
  };
  const screenPointOf = (id: string): { x: number; y: number } | null => {
    if (!model) return null;
    const box = new THREE.Box3();
    for (const mesh of model.meshesOf(id)) box.expandByObject(mesh);
    if (box.isEmpty()) return null;
    const rect = canvas.getBoundingClientRect();
    const point = new THREE.Vector3();
    camera.updateMatrixWorld();
    // Points through the box, centre first: the first one a click there would pick.
    const steps = [0.5, 0.3, 0.7, 0.15, 0.85];
    for (const fx of steps) {
      for (const fy of steps) {
        for (const fz of steps) {
          point.set(
            THREE.MathUtils.lerp(box.min.x, box.max.x, fx),
            THREE.MathUtils.lerp(box.min.y, box.max.y, fy),
            THREE.MathUtils.lerp(box.min.z, box.max.z, fz),
          );
          const ndc = point.clone().project(camera);
          if (Math.abs(ndc.x) > 0.95 || Math.abs(ndc.y) > 0.95 || ndc.z > 1) continue;
          const x = rect.left + ((ndc.x + 1) / 2) * rect.width;
          const y = rect.top + ((1 - ndc.y) / 2) * rect.height;
          if (objectAt(x, y) === id) return { x, y };
        }
      }
    }
    return null;
  };

  let pressed: { x: number; y: number } | null = null;
  canvas.addEventListener("pointerdown", (event) => {
    pressed = event.button === 0 ? { x: event.clientX, y: event.clientY } : null;
  });
  canvas.addEventListener("pointerup", (event) => {
    if (!pressed || event.button !== 0) return;
    const moved = Math.hypot(event.clientX - pressed.x, event.clientY - pressed.y);
    pressed = null;
    if (moved <= CLICK_SLOP) session.select(objectAt(event.clientX, event.clientY));
  });
  canvas.addEventListener("pointermove", (event) => {
    if (event.buttons === 0) session.hover(objectAt(event.clientX, event.clientY));
  });
  canvas.addEventListener("pointerleave", () => session.hover(null));

  // Objects in 3D have the colours of their masks on the photo.
  const colours = () => maskColours(session.objects, maskStyle.get().colouring);
  const stopColours = maskStyle.subscribe(() => {
    model?.recolour(colours());
    requestRender();
  });

  const highlight = () => {
    canvas.dataset.selected = session.selected ?? "";
    if (!model) return;
    model.highlight(new Set([session.hovered, session.selected].filter((id) => id !== null)));
    requestRender();
  };

  const unsubscribe = session.subscribe((change) => {
    if (change === "hover" || change === "select") highlight();
    else if (change === "edits") showLive();
    else if (change === "document") {
      showLive();
      if (glbKey(session.doc) !== loadedGlb) void loadSafely();
    }
  });
  // The layout draft is updated before the session announces a change: SceneSession hands a
  // new document to the draft (layout.setDocument: re-fit the moved corners, or show the
  // stored room) before it emits "document", and undo/redo re-fit the draft before it emits
  // "edits". So layout.live is already current whichever event the view hears first; the
  // draft's own events (drags, fits) redraw the room as well, and a second showLive for the
  // same change only draws the same room again.
  const unsubscribeLayout = layout?.subscribe(showLive) ?? (() => {});

  return () => {
    abort.abort();
    unsubscribe();
    stopColours();
    unsubscribeLayout();
    observer.disconnect();
    cancelAnimationFrame(frame);
    clearTimeout(still);
    controls.dispose();
    model?.dispose();
    room.dispose();
    arrows.dispose();
    frustum?.dispose();
    delete canvas.scene3dProbe;
    renderer.dispose();
    renderer.forceContextLoss();
  };
}
