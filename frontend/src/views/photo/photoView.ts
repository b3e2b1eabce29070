// The photo with its overlays: masks, support arrows, labels; hover and click pick objects.
import type { SceneObject } from "@holiscene/schema";
import { api } from "../../api/client";
import { el, svgEl } from "../../dom";
import { mountArrowEditing } from "../../editors/arrowEditing";
import { mountObjectEditBar } from "../../editors/objectEditBar";
import { mountPhotoTools, type PhotoTools, toolOverlay } from "../../editors/photoTools";
import { registerShortcut } from "../../shortcuts";
import type { ObjectEditor } from "../../state/objectEditor";
import type { SceneSession } from "../../state/sceneSession";
import type { Rgb } from "../classColors";
import { maskColours } from "../objectColors";
import { frameFor, strokeWidth } from "./arrowGeometry";
import { renderArrows } from "./arrowLayer";
import { renderLabels } from "./labelLayer";
import { renderMasks, renderOutlines } from "./maskLayer";
import { HitMap, objectRegion, type Region } from "./maskRaster";
import { maskStyle, maskStyleControls } from "./maskStyle";
import { mountPhotoZoom } from "./photoZoom";

function toggle(label: string, testid: string, onChange: (on: boolean) => void) {
  const input = el("input", {
    testid,
    attrs: { type: "checkbox", checked: true },
    on: { change: () => onChange(input.checked) },
  });
  return { input, label: el("label", { className: "toggle" }, input, label) };
}

function legend(): HTMLElement {
  const item = (className: string, text: string) =>
    el(
      "span",
      { className: "legend-item" },
      el("span", { className: `swatch ${className}` }),
      text,
    );
  return el(
    "div",
    { className: "legend", attrs: { "aria-label": "Arrow colours" } },
    item("swatch--below", "supported from below"),
    item("swatch--behind", "from behind"),
    item("swatch--pending", "not saved"),
    item("swatch--suggested", "suggested by the model"),
  );
}

/** A key for the parts of the objects that the masks and hit map depend on. */
const geometryKey = (objects: readonly SceneObject[]) =>
  JSON.stringify(objects.map((o) => [o.id, o.class, o.bbox, o.mask]));

export interface PhotoViewHandle {
  /** The photo's tools: others add theirs (box, mask tools) with `tools.add`. */
  tools: PhotoTools;
  dispose(): void;
}

export function mountPhotoView(
  container: HTMLElement,
  session: SceneSession,
  objectEditor: ObjectEditor,
): PhotoViewHandle {
  const { width, height } = session.doc.scene.image;
  const frame = frameFor(width, height);
  const m = frame.margin;
  const masks = svgEl("g", { class: "masks", "data-testid": "mask-layer" });
  const outlines = svgEl("g", { class: "outlines" });
  const arrows = svgEl("g", { class: "arrows", "data-testid": "arrow-layer" });
  const labels = svgEl("g", { class: "labels" });
  const overlay = toolOverlay();
  const photo = svgEl("image", {
    href: api.imageUrl(session.sceneId),
    x: 0,
    y: 0,
    width,
    height,
    preserveAspectRatio: "none",
    "data-testid": "photo-image",
  });
  const svg = svgEl(
    "svg",
    {
      class: "photo-svg",
      "data-testid": "photo",
      viewBox: `${-m} ${-m} ${width + 2 * m} ${height + 2 * m}`,
      role: "img",
      "aria-label": `Photo of ${session.doc.scene.name} with masks and support arrows`,
    },
    svgEl("rect", {
      class: "photo-frame",
      x: -m,
      y: -m,
      width: width + 2 * m,
      height: height + 2 * m,
    }),
    photo,
    masks,
    outlines,
    arrows,
    labels,
    overlay,
  );
  const status = el("p", { className: "photo-status", testid: "photo-status" });
  photo.addEventListener("load", () => {
    status.textContent = "";
    svg.dataset.loaded = "true";
  });
  photo.addEventListener("error", () => {
    status.textContent = "The photo could not be loaded.";
  });

  const setLayer = (layer: SVGGElement) => (on: boolean) => {
    layer.style.display = on ? "" : "none";
  };
  const layerToggles = [
    { key: "M", name: "masks", ...toggle("Masks", "toggle-masks", setLayer(masks)) },
    { key: "H", name: "arrows", ...toggle("Arrows", "toggle-arrows", setLayer(arrows)) },
    { key: "L", name: "labels", ...toggle("Labels", "toggle-labels", setLayer(labels)) },
  ];
  const removeKeys = layerToggles.map(({ key, name, input }) =>
    registerShortcut({
      keys: key,
      description: `Hide or show the ${name}`,
      scope: "Photo",
      run: () => input.click(),
    }),
  );
  const styleControls = maskStyleControls();
  const toolbar = el("div", { className: "photo-toolbar", testid: "photo-tools" });
  container.replaceChildren(
    toolbar,
    el(
      "div",
      { className: "photo-toolbar" },
      ...layerToggles.map((t) => t.label),
      styleControls.element,
      legend(),
    ),
    el("div", { className: "photo-box" }, svg),
    status,
  );

  let regions = new Map<string, Region>();
  let hitMap: HitMap | null = null;
  let colours = new Map<string, Rgb>();
  let drawnGeometry = "";

  const drawGeometry = () => {
    const objects = session.objects;
    const { colouring, opacity } = maskStyle.get();
    svg.style.setProperty("--mask-opacity", String(opacity));
    const key = `${colouring} ${geometryKey(objects)}`;
    if (key === drawnGeometry) return;
    drawnGeometry = key;
    const placed = objects.map((object) => ({ object, region: objectRegion(object) }));
    regions = new Map(placed.map((p) => [p.object.id, p.region]));
    hitMap = new HitMap(width, height, placed);
    colours = maskColours(objects, colouring);
    renderMasks(masks, objects, regions, colours);
  };
  // 1 / the zoom: arrows and labels keep their size on the screen.
  let overlayScale = 1;
  const drawSupports = () => {
    const { objects } = session;
    const shown = session.shown();
    const suggested = session.suggestions();
    const anchors = renderArrows(arrows, objects, regions, shown, frame, suggested, overlayScale);
    renderLabels(labels, objects, regions, shown, frame, colours, anchors, overlayScale);
  };
  const drawHighlight = () => {
    const { hovered, selected } = session;
    svg.classList.toggle("has-hover", hovered !== null);
    for (const node of svg.querySelectorAll<SVGElement>("[data-object], [data-child]")) {
      const id = node.dataset.object ?? node.dataset.child;
      node.classList.toggle("is-hovered", id === hovered);
      node.classList.toggle("is-selected", id === selected);
      // An arrow from the hovered object to what it holds up stays in view too.
      node.classList.toggle("is-related", hovered !== null && node.dataset.parent === hovered);
    }
    renderOutlines(
      outlines,
      session.objects,
      hovered,
      selected,
      strokeWidth(frame) * 0.8 * overlayScale,
      colours,
    );
  };
  const drawAll = () => {
    drawGeometry();
    drawSupports();
    drawHighlight();
  };

  const toImage = (event: MouseEvent): [number, number] | null => {
    const matrix = svg.getScreenCTM();
    if (!matrix) return null;
    const point = new DOMPoint(event.clientX, event.clientY).matrixTransform(matrix.inverse());
    return [point.x, point.y];
  };
  const maskAt = (event: MouseEvent): string | null => {
    const point = toImage(event);
    return point && hitMap ? hitMap.at(point[0], point[1]) : null;
  };
  const objectAt = (event: MouseEvent): string | null => {
    const arrow = (event.target as Element).closest<SVGGElement>("[data-child]");
    return arrow?.dataset.child ?? maskAt(event);
  };
  svg.addEventListener("mousemove", (event) => session.hover(objectAt(event)));
  svg.addEventListener("mouseleave", () => session.hover(null));
  const stopEditing = mountArrowEditing(
    {
      svg,
      objectAt: maskAt,
      toImage,
      centroid: (id) => regions.get(id)?.centroid ?? null,
      bbox: (id) => session.object(id)?.bbox ?? null,
      strokeWidth: () => strokeWidth(frame),
    },
    session,
  );

  // Before the tools: a pan's press is nobody else's.
  const zoom = mountPhotoZoom(svg, { x: -m, y: -m, width: width + 2 * m, height: height + 2 * m });
  const tools = mountPhotoTools(toolbar, {
    svg,
    overlay,
    session,
    objects: objectEditor,
    width,
    height,
    toImage,
    objectAt: maskAt,
    pixelSize: () => 1 / (svg.getScreenCTM()?.a || 1),
    onView: (listener) => zoom.onChange(listener),
  });
  toolbar.append(zoom.controls);
  const stopEditBar = mountObjectEditBar(toolbar, objectEditor);
  // Arrows and labels keep their size on the screen when the photo is zoomed (placed again).
  const stopZoomLabels = zoom.onChange(() => {
    if (1 / zoom.zoom === overlayScale) return;
    overlayScale = 1 / zoom.zoom;
    drawSupports();
    drawHighlight();
  });

  drawAll();
  const stopStyle = maskStyle.subscribe(drawAll);
  const unsubscribe = session.subscribe((change) => {
    if (change === "document") drawAll();
    else if (change === "edits" || change === "suggestions") {
      drawSupports();
      drawHighlight();
    } else if (change === "hover" || change === "select") drawHighlight();
  });
  return {
    tools,
    dispose: () => {
      tools.dispose();
      zoom.dispose();
      stopZoomLabels();
      stopEditBar();
      unsubscribe();
      stopStyle();
      styleControls.dispose();
      stopEditing();
      for (const remove of removeKeys) remove();
    },
  };
}
