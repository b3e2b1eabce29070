// The photo with its overlays: masks, support arrows, labels; hover and click pick objects.
// Its parts: photoSvg (the photo and its layers), layerBar (layer toggles, mask style),
// photoOverlays (what the layers show), photoZoom, depthKey (the depth overlay's colours), and
// the editors' tools on the photo.
import { el } from "../../dom";
import { mountArrowEditing } from "../../editors/arrowEditing";
import { mountObjectEditBar } from "../../editors/objectEditBar";
import { mountPhotoTools, type PhotoTools } from "../../editors/photoTools";
import type { ObjectEditor } from "../../state/objectEditor";
import type { SceneSession } from "../../state/sceneSession";
import { strokeWidth } from "./arrowGeometry";
import { depthKey } from "./depthKey";
import { layerBar } from "./layerBar";
import { maskStyle } from "./maskStyle";
import { PhotoOverlays } from "./photoOverlays";
import { photoSvg, toImage } from "./photoSvg";
import { mountPhotoZoom } from "./photoZoom";

export interface PhotoViewHandle {
  /** The photo's tools: others add theirs (box, mask tools) with `tools.add`. */
  tools: PhotoTools;
  /** The layer toggles and mask style, for the caller to put under the photo (above it they
   * pushed the photo a line further below the fold). */
  viewOptions: HTMLElement;
  dispose(): void;
}

export function mountPhotoView(
  container: HTMLElement,
  session: SceneSession,
  objectEditor: ObjectEditor,
): PhotoViewHandle {
  const { width, height } = session.doc.scene.image;
  const { svg, layers, frame, status } = photoSvg(session);
  const m = frame.margin;
  const key = layers.depth ? depthKey(session.sceneId) : null;
  const layersBar = layerBar(layers, key ?? undefined);
  const toolbar = el("div", { className: "photo-toolbar photo-tool-row", testid: "photo-tools" });
  const photoBox = el("div", { className: "photo-box" }, svg);
  container.replaceChildren(toolbar, photoBox, status);
  const overlays = new PhotoOverlays(svg, layers, frame, session);

  const pointOf = (event: MouseEvent) => toImage(svg, event);
  const maskAt = (event: MouseEvent): string | null => {
    const point = pointOf(event);
    if (!point) return null;
    return overlays.labelAt(point[0], point[1]) ?? overlays.objectAt(point[0], point[1]);
  };
  const objectAt = (event: MouseEvent): string | null => {
    const arrow = (event.target as Element).closest<SVGGElement>("[data-child]");
    return arrow?.dataset.child ?? maskAt(event);
  };
  const stopEditing = mountArrowEditing(
    {
      svg,
      objectAt: maskAt,
      toImage: pointOf,
      centroid: (id) => overlays.centroid(id),
      bbox: (id) => session.object(id)?.bbox ?? null,
      strokeWidth: () => strokeWidth(frame),
    },
    session,
  );

  // Before the tools: a pan's press is nobody else's.
  const zoom = mountPhotoZoom(svg, { x: -m, y: -m, width: width + 2 * m, height: height + 2 * m });
  const tools = mountPhotoTools(toolbar, {
    svg,
    overlay: layers.overlay,
    session,
    objects: objectEditor,
    width,
    height,
    toImage: pointOf,
    objectAt: maskAt,
    pixelSize: () => 1 / (svg.getScreenCTM()?.a || 1),
    onView: (listener) => zoom.onChange(listener),
  });
  toolbar.append(zoom.controls);
  const hovering = (event: MouseEvent) =>
    tools.active.drawsOnSelected && session.selectedObject ? null : objectAt(event);
  svg.addEventListener("mousemove", (event) => session.hover(hovering(event)));
  svg.addEventListener("mouseleave", () => session.hover(null));
  const stopEditBar = mountObjectEditBar(toolbar, photoBox, svg, objectEditor);
  // The sticky tool row's height, for what sticks under it (the detector's bar).
  const toolHeight =
    typeof ResizeObserver === "undefined"
      ? null
      : new ResizeObserver(() =>
          container.style.setProperty("--photo-tools-height", `${toolbar.offsetHeight}px`),
        );
  toolHeight?.observe(toolbar);
  // Arrows and labels keep their size on the screen when the photo is zoomed (placed again).
  const stopZoomLabels = zoom.onChange(() => overlays.setZoom(zoom.zoom));

  const drawAll = () => overlays.drawAll();
  drawAll();
  const stopStyle = maskStyle.subscribe(drawAll);
  const unsubscribe = session.subscribe((change) => {
    if (change === "document") drawAll();
    else if (change === "edits" || change === "suggestions") {
      overlays.drawSupports();
      overlays.drawHighlight();
    } else if (change === "hover" || change === "select") overlays.drawHighlight();
  });
  return {
    tools,
    viewOptions: layersBar.element,
    dispose: () => {
      tools.dispose();
      zoom.dispose();
      stopZoomLabels();
      stopEditBar();
      toolHeight?.disconnect();
      unsubscribe();
      stopStyle();
      stopEditing();
      layersBar.dispose();
      key?.dispose();
    },
  };
}
