// The 3D panel: scene.glb in three.js, seen first from the photo's camera, orbitable.
// It renders on demand (orbit, resize, hover), which keeps software WebGL cheap.
import type { Camera } from "@holiscene/schema";
import * as THREE from "three";
import { OrbitControls } from "three/examples/jsm/controls/OrbitControls.js";
import { api } from "../../api/client";
import { el } from "../../dom";
import type { SceneSession } from "../../state/sceneSession";
import { isRoomSurface, SceneModel } from "./sceneModel";

type Status = "loading" | "ready" | "missing" | "error" | "no-webgl";

/** The photo camera's vertical field of view in degrees (55 when K is unknown). */
function verticalFov(camera: Camera | null | undefined, imageHeight: number): number {
  const fy = camera?.K[1][1];
  return fy ? THREE.MathUtils.radToDeg(2 * Math.atan(imageHeight / 2 / fy)) : 55;
}

function createRenderer(canvas: HTMLCanvasElement): THREE.WebGLRenderer | null {
  try {
    // preserveDrawingBuffer lets tests (and "save image") read the pixels after a frame.
    return new THREE.WebGLRenderer({ canvas, antialias: true, preserveDrawingBuffer: true });
  } catch {
    return null;
  }
}

export function mountScene3d(container: HTMLElement, session: SceneSession): () => void {
  const canvas = el("canvas", {
    testid: "scene3d-canvas",
    attrs: { tabindex: 0, "aria-label": "3D scene: drag to orbit, scroll to zoom" },
  });
  const status = el("p", { className: "scene3d-status", testid: "scene3d-status" });
  const viewButton = (text: string, testid: string) =>
    el("button", { text, testid, attrs: { type: "button", disabled: true } });
  const overviewButton = viewButton("Overview", "scene3d-overview");
  const photoViewButton = viewButton("Photo viewpoint", "scene3d-photo-view");
  const viewport = el("div", { className: "scene3d-viewport" }, canvas, status);
  container.replaceChildren(
    el(
      "div",
      { className: "panel-toolbar" },
      el("span", { className: "hint", text: "Drag to orbit, right-drag to pan, scroll to zoom" }),
      el("span", { className: "spacer" }),
      overviewButton,
      photoViewButton,
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
  scene.add(new THREE.HemisphereLight(0xffffff, 0x8a8577, 2.2));
  const sun = new THREE.DirectionalLight(0xffffff, 1.6);
  sun.position.set(-2, 6, 3);
  scene.add(sun);

  const { image, camera: photoCamera } = session.doc.scene;
  const camera = new THREE.PerspectiveCamera(verticalFov(photoCamera, image.height), 1, 0.05, 200);
  const controls = new OrbitControls(camera, canvas);
  controls.enableDamping = false;

  let frame = 0;
  const render = () => {
    frame = 0;
    renderer.render(scene, camera);
  };
  const requestRender = () => {
    frame ||= requestAnimationFrame(render);
  };
  controls.addEventListener("change", requestRender);

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
  let objects = new THREE.Sphere(new THREE.Vector3(3, 0, 0), 2);

  /** Look at the objects from above and behind the photo's camera, all in view. */
  const overview = () => {
    const centre = objects.center;
    const back = new THREE.Vector3(-centre.x, 0, -centre.z);
    if (back.lengthSq() < 1e-6) back.set(-1, 0, 0);
    const elevation = THREE.MathUtils.degToRad(35);
    const direction = back
      .normalize()
      .multiplyScalar(Math.cos(elevation))
      .setY(Math.sin(elevation));
    const vertical = THREE.MathUtils.degToRad(camera.fov);
    const horizontal = 2 * Math.atan(Math.tan(vertical / 2) * camera.aspect);
    const distance = (objects.radius / Math.sin(Math.min(vertical, horizontal) / 2)) * 1.05;
    camera.position.copy(centre).addScaledVector(direction, distance);
    controls.target.copy(centre);
    controls.update();
    requestRender();
  };

  /** Stand at the photo's camera (the origin), looking down by its pitch. */
  const photoView = () => {
    const pitch = THREE.MathUtils.degToRad(photoCamera?.pitch_deg ?? 0);
    const distance = Math.max(1, objects.center.length());
    camera.position.set(0, 0, 0);
    controls.target.set(distance * Math.cos(pitch), -distance * Math.sin(pitch), 0);
    controls.update();
    requestRender();
  };
  overviewButton.addEventListener("click", overview);
  photoViewButton.addEventListener("click", photoView);

  const abort = new AbortController();
  const load = async () => {
    setStatus("loading", "Loading the 3D scene…");
    const response = await fetch(api.glbUrl(session.sceneId, session.doc.revision), {
      signal: abort.signal,
    });
    if (response.status === 404) {
      setStatus("missing", "No 3D scene yet: it appears once the pipeline has run.");
      return;
    }
    if (!response.ok) throw new Error(`scene.glb: ${response.status} ${response.statusText}`);
    const loaded = await SceneModel.parse(await response.arrayBuffer(), session.objects);
    if (abort.signal.aborted) {
      loaded.dispose();
      return;
    }
    model = loaded;
    scene.add(model.root);
    objects = model.objectBounds().getBoundingSphere(new THREE.Sphere());
    overviewButton.disabled = false;
    photoViewButton.disabled = false;
    resize();
    overview();
    render();
    setStatus("ready", "");
  };
  load().catch((error: unknown) => {
    if (abort.signal.aborted) return;
    setStatus("error", `The 3D scene could not be shown: ${String(error)}`);
  });

  // Hover and click in 3D pick objects, like on the photo.
  const raycaster = new THREE.Raycaster();
  const objectAt = (event: MouseEvent): string | null => {
    if (!model) return null;
    const rect = canvas.getBoundingClientRect();
    const ndc = new THREE.Vector2(
      ((event.clientX - rect.left) / rect.width) * 2 - 1,
      -((event.clientY - rect.top) / rect.height) * 2 + 1,
    );
    raycaster.setFromCamera(ndc, camera);
    for (const hit of raycaster.intersectObject(model.root, true)) {
      const id: unknown = hit.object.userData.objectId;
      if (typeof id === "string" && !isRoomSurface(id)) return id;
    }
    return null;
  };
  canvas.addEventListener("pointermove", (event) => {
    if (event.buttons === 0) session.hover(objectAt(event));
  });
  canvas.addEventListener("pointerleave", () => session.hover(null));
  canvas.addEventListener("dblclick", (event) => session.select(objectAt(event)));

  const unsubscribe = session.subscribe((change) => {
    if ((change === "hover" || change === "select") && model) {
      model.highlight(new Set([session.hovered, session.selected].filter((id) => id !== null)));
      requestRender();
    }
  });

  return () => {
    abort.abort();
    unsubscribe();
    observer.disconnect();
    cancelAnimationFrame(frame);
    controls.dispose();
    model?.dispose();
    renderer.dispose();
    renderer.forceContextLoss();
  };
}
