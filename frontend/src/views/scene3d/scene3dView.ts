// The 3D panel: scene.glb in three.js with the room, the photo's camera frustum (the photo on
// its image plane) and the support arrows; first seen from above and behind the camera,
// orbitable. The room and the frustum follow the layout editor live. Clicking an object
// selects it here and on the photo (the session's selection). It renders on demand (orbit,
// resize, hover, layout change), which keeps software WebGL cheap.
import * as THREE from "three";
import { deferred } from "../../afterPaint";
import { api } from "../../api/client";
import type { LayoutDraft } from "../../state/layoutDraft";
import type { SceneSession } from "../../state/sceneSession";
import { mountDepthPoints } from "./depthPoints";
import { objectCaption } from "./objectCaption";
import { downloadCanvasPng, pngFileName } from "./pngExport";
import { ViewportCamera } from "./viewportCamera";
import { buildViewportDom } from "./viewportDom";
import { ViewportLabels } from "./viewportLabels";
import { LiveLayers } from "./viewportLive";
import { ViewportObjects } from "./viewportObjects";
import { ViewportPicking } from "./viewportPicking";
import { scene3dProbe } from "./viewportProbe";
import { createRenderer, type FrameStats, ViewportRender } from "./viewportRender";

// Its parts, one file each: viewportDom (toolbar, canvas, status line), viewportRender (frames
// on demand), viewportCamera (orbit, overview, photo viewpoint), viewportLive (room, frustum,
// arrows), viewportObjects (the GLB's objects), viewportPicking (hover and click), depthPoints
// (each object's points from the depth, for scenes with depth), viewportLabels (the objects'
// ids over the view), and viewportProbe (what end-to-end tests read).
export type { ProbedCanvas, Scene3dProbe } from "./viewportDom";

export function mountScene3d(
  container: HTMLElement,
  session: SceneSession,
  layout: LayoutDraft | null = null,
): () => void {
  const dom = buildViewportDom(container);
  const { canvas, setStatus } = dom;
  const renderer = createRenderer(canvas);
  if (!renderer) {
    setStatus("no-webgl", "The 3D view needs WebGL, which this browser does not provide.");
    return () => {};
  }
  const scene = new THREE.Scene();
  scene.background = new THREE.Color(0xe8ecf1);
  // No lights: objects and arrows are lit once, when baked (bakedMesh.ts), the room is flat.

  const requestRender = () => frames.requestRender();
  const live = new LiveLayers(scene, requestRender);
  const { image, camera: photoCamera } = session.doc.scene;
  const view = new ViewportCamera(canvas, photoCamera, image.height, requestRender);
  const stats: FrameStats = { frames: 0, renderMs: [] };
  const frames = new ViewportRender({
    renderer,
    scene,
    camera: view.camera,
    controls: view.controls,
    canvas,
    viewport: dom.viewport,
    stats,
    afterFrame: () => labels.update(),
  });

  /** The room, frustum and arrows for the current revision and layout draft. */
  const showLive = () => {
    const room = live.show(session, layout, api.imageUrl(session.sceneId));
    objects.model?.setRoomVisible(room === null);
  };
  /** Frame the objects, or the room when there are none. */
  const fitFocus = () => {
    const bounds = objects.model?.objectBounds() ?? new THREE.Box3();
    if (bounds.isEmpty() && live.room.room) {
      for (const corner of live.room.corners()) bounds.expandByPoint(new THREE.Vector3(...corner));
    }
    view.fitFocus(bounds);
  };
  const objects = new ViewportObjects({
    scene,
    session,
    canvas,
    setStatus,
    requestRender,
    onMissing: () => {
      fitFocus();
      view.overview();
    },
    onShown: (first) => {
      showLive();
      fitFocus();
      frames.resize();
      if (first) view.overview();
      frames.render();
      setStatus("ready", "");
    },
  });
  const picking = new ViewportPicking(canvas, view.camera, () => objects.model);
  const labels = new ViewportLabels({
    viewport: dom.viewport,
    toolbar: dom.extras,
    camera: view.camera,
    session,
    model: () => objects.model,
    colours: () => objects.colours(),
    requestRender,
  });
  const depthPoints = session.doc.scene.depth
    ? mountDepthPoints({
        scene,
        session,
        toolbar: dom.extras,
        viewport: dom.viewport,
        seeThrough: (on) => {
          objects.setSeeThrough(on);
          live.setPhotoSeeThrough(on);
        },
        requestRender,
      })
    : null;
  canvas.scene3dProbe = scene3dProbe({
    stats,
    renderer,
    frames,
    view,
    live,
    objects,
    picking,
    depthPoints: depthPoints?.clouds ?? null,
  });

  dom.overviewButton.addEventListener("click", view.overview);
  dom.photoViewButton.addEventListener("click", () =>
    view.photoView(live.frustum?.pitchRoll.pitchDeg ?? 0),
  );
  dom.exportButton.addEventListener("click", () => {
    const name = pngFileName(session.doc.scene.name, session.doc.revision);
    downloadCanvasPng(canvas, name, frames.render).catch((error: unknown) => {
      setStatus("error", `Export failed: ${String(error)}`);
    });
  });
  for (const button of [dom.overviewButton, dom.photoViewButton, dom.exportButton]) {
    button.disabled = false;
  }
  showLive();
  void objects.load();
  picking.listen(session);

  // An edit is followed here after the photo has drawn it: a frame of this view (software
  // WebGL on machines without a GPU) would otherwise hold the photo's redraw back.
  let newDocument = false;
  const follow = deferred(() => {
    showLive();
    if (!newDocument) return;
    newDocument = false;
    if (objects.stale) void objects.load();
    depthPoints?.refresh();
  });
  // The object pointed at, else the selected one, named over the view with its box's size.
  const showCaption = () => {
    const id = session.hovered ?? session.selected;
    const object = id === null ? undefined : session.object(id);
    dom.setCaption(object ? objectCaption(object) : "");
  };
  const unsubscribe = session.subscribe((change) => {
    if (change === "hover" || change === "select" || change === "document") showCaption();
    if (change === "hover" || change === "select") objects.highlight();
    else if (change === "edits") follow();
    else if (change === "document") {
      newDocument = true;
      follow();
    }
  });
  // The layout draft is updated before the session announces a change: SceneSession hands a
  // new document to the draft (layout.setDocument: re-fit the moved corners, or show the
  // stored room) before it emits "document", and undo/redo re-fit the draft before it emits
  // "edits". So layout.live is already current whichever event the view hears first; the
  // draft's own events (drags, fits) redraw the room as well, and a second showLive for the
  // same change only draws the same room again. The draft's "document" is left to the
  // session's, which this view follows after the photo has drawn the revision.
  const unsubscribeLayout =
    layout?.subscribe((change) => {
      if (change !== "document") showLive();
    }) ?? (() => {});

  return () => {
    follow.cancel();
    unsubscribe();
    unsubscribeLayout();
    objects.dispose();
    labels.dispose();
    depthPoints?.dispose();
    frames.dispose();
    view.dispose();
    live.dispose();
    delete canvas.scene3dProbe;
    renderer.dispose();
    renderer.forceContextLoss();
  };
}
