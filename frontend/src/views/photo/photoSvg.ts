// The photo's SVG: the photo in a frame (whose margin holds arrows to the walls and floor),
// and the layers drawn over it, bottom to top: depth (when the photo came with it, hidden at
// first), masks, outlines, arrows, labels, the tools'.

import { api } from "../../api/client";
import { el, svgEl } from "../../dom";
import { toolOverlay } from "../../editors/photoTools";
import type { SceneSession } from "../../state/sceneSession";
import { type Frame, frameFor } from "./arrowGeometry";

export interface PhotoLayers {
  /** The depth as colours over the photo; null for a photo without depth. */
  depth: SVGGElement | null;
  masks: SVGGElement;
  outlines: SVGGElement;
  arrows: SVGGElement;
  labels: SVGGElement;
  /** Where the photo tools draw. */
  overlay: SVGGElement;
}

export interface PhotoSvg {
  svg: SVGSVGElement;
  layers: PhotoLayers;
  frame: Frame;
  /** Says when the photo could not be loaded. */
  status: HTMLElement;
}

export function photoSvg(session: SceneSession): PhotoSvg {
  const { width, height } = session.doc.scene.image;
  const frame = frameFor(width, height);
  const m = frame.margin;
  const layers: PhotoLayers = {
    depth: session.doc.scene.depth ? depthLayer(session.sceneId, width, height) : null,
    masks: svgEl("g", { class: "masks", "data-testid": "mask-layer" }),
    outlines: svgEl("g", { class: "outlines" }),
    arrows: svgEl("g", { class: "arrows", "data-testid": "arrow-layer" }),
    labels: svgEl("g", { class: "labels" }),
    overlay: toolOverlay(),
  };
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
    ...(layers.depth ? [layers.depth] : []),
    layers.masks,
    layers.outlines,
    layers.arrows,
    layers.labels,
    layers.overlay,
  );
  const status = el("p", { className: "photo-status", testid: "photo-status" });
  photo.addEventListener("load", () => {
    status.textContent = "";
    svg.dataset.loaded = "true";
  });
  photo.addEventListener("error", () => {
    status.textContent = "The photo could not be loaded.";
  });
  return { svg, layers, frame, status };
}

function depthLayer(sceneId: string, width: number, height: number): SVGGElement {
  const image = svgEl("image", {
    href: api.depthPreviewUrl(sceneId),
    x: 0,
    y: 0,
    width,
    height,
    preserveAspectRatio: "none",
    "data-testid": "depth-image",
  });
  // Translucent: the photo shows through, so edges in the depth can be matched to the photo's.
  const layer = svgEl("g", { class: "depth", opacity: 0.7, "data-testid": "depth-layer" }, image);
  layer.style.display = "none";
  return layer;
}

/** Where a mouse event is on the photo, in photo pixels (null while the SVG is not shown). */
export function toImage(svg: SVGSVGElement, event: MouseEvent): [number, number] | null {
  const matrix = svg.getScreenCTM();
  if (!matrix) return null;
  const point = new DOMPoint(event.clientX, event.clientY).matrixTransform(matrix.inverse());
  return [point.x, point.y];
}
