// What is drawn over the photo: the masks (and the hit map that tells which object is under a
// point), the support arrows and labels (kept their size on the screen when zoomed), and the
// hovered and selected objects' highlight.
import type { SceneObject } from "@holiscene/schema";
import type { SceneSession } from "../../state/sceneSession";
import type { Rgb } from "../classColors";
import { maskColours } from "../objectColors";
import { type Frame, strokeWidth } from "./arrowGeometry";
import { renderArrows } from "./arrowLayer";
import { renderLabels } from "./labelLayer";
import { renderMasks, renderOutlines } from "./maskLayer";
import { HitMap, objectRegion, type Region } from "./maskRaster";
import { maskStyle } from "./maskStyle";
import type { PhotoLayers } from "./photoSvg";

/** A key for the parts of the objects that the masks and hit map depend on. */
const geometryKey = (objects: readonly SceneObject[]) =>
  JSON.stringify(objects.map((o) => [o.id, o.class, o.bbox, o.mask]));

export class PhotoOverlays {
  private regions = new Map<string, Region>();
  private hitMap: HitMap | null = null;
  private colours = new Map<string, Rgb>();
  private drawnGeometry = "";
  /** 1 / the zoom: arrows and labels keep their size on the screen. */
  private overlayScale = 1;

  constructor(
    private readonly svg: SVGSVGElement,
    private readonly layers: PhotoLayers,
    private readonly frame: Frame,
    private readonly session: SceneSession,
  ) {}

  /** The object whose mask covers a photo point, or null. */
  objectAt(x: number, y: number): string | null {
    return this.hitMap ? this.hitMap.at(x, y) : null;
  }

  /** The centre of the object's mask (for arrows drawn to it). */
  centroid(id: string): [number, number] | null {
    return this.regions.get(id)?.centroid ?? null;
  }

  /** Masks and the hit map, when the objects' geometry or the colouring changed. */
  drawGeometry(): void {
    const objects = this.session.objects;
    const { colouring, opacity } = maskStyle.get();
    this.svg.style.setProperty("--mask-opacity", String(opacity));
    const key = `${colouring} ${geometryKey(objects)}`;
    if (key === this.drawnGeometry) return;
    this.drawnGeometry = key;
    const { width, height } = this.session.doc.scene.image;
    const placed = objects.map((object) => ({ object, region: objectRegion(object) }));
    this.regions = new Map(placed.map((p) => [p.object.id, p.region]));
    this.hitMap = new HitMap(width, height, placed);
    this.colours = maskColours(objects, colouring);
    renderMasks(this.layers.masks, objects, this.regions, this.colours);
  }

  /** The support arrows and the labels. */
  drawSupports(): void {
    const { session, layers, frame, regions, overlayScale } = this;
    const { objects } = session;
    const shown = session.shown();
    const suggested = session.suggestions();
    const anchors = renderArrows(
      layers.arrows,
      objects,
      regions,
      shown,
      frame,
      suggested,
      overlayScale,
    );
    renderLabels(
      layers.labels,
      objects,
      regions,
      shown,
      frame,
      this.colours,
      anchors,
      overlayScale,
    );
  }

  /** The hovered and selected objects, their masks, arrows and outlines. */
  drawHighlight(): void {
    const { svg, session } = this;
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
      this.layers.outlines,
      session.objects,
      hovered,
      selected,
      strokeWidth(this.frame) * 0.8 * this.overlayScale,
      this.colours,
    );
  }

  drawAll(): void {
    this.drawGeometry();
    this.drawSupports();
    this.drawHighlight();
  }

  /** Draw arrows and labels for a new zoom (if it changed). */
  setZoom(zoom: number): void {
    if (1 / zoom === this.overlayScale) return;
    this.overlayScale = 1 / zoom;
    this.drawSupports();
    this.drawHighlight();
  }
}
