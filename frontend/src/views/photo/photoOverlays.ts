// What is drawn over the photo: the masks (and the hit map that tells which object is under a
// point), the support arrows and labels (kept their size on the screen when zoomed), and the
// hovered and selected objects' highlight.
import type { SceneObject } from "@holiscene/schema";
import { placeChildren } from "../../dom";
import type { SceneSession } from "../../state/sceneSession";
import { maskColours } from "../objectColors";
import type { Rgb } from "../rgb";
import { type Frame, strokeWidth } from "./arrowGeometry";
import { renderArrows } from "./arrowLayer";
import { drawnLabelTags, renderLabels } from "./labelLayer";
import { GREY, maskNode, renderOutlines } from "./maskLayer";
import { HitMap, objectRegion, type Region } from "./maskRaster";
import { maskStyle } from "./maskStyle";
import type { PhotoLayers } from "./photoSvg";

/** What an object's mask node depends on: its mask (or box, without one) and its colour. */
function maskKey(object: SceneObject, colour: Rgb): string {
  const { mask } = object;
  const shape = mask
    ? `${mask.source}|${mask.origin.join()}|${mask.size.join()}|${mask.rle.join()}`
    : `box|${object.bbox.join()}`;
  return `${colour.join()}|${shape}`;
}

/** One object as drawn in the mask layer. */
interface DrawnMask {
  key: string;
  region: Region;
  node: SVGElement;
}

export class PhotoOverlays {
  private drawn = new Map<string, DrawnMask>();
  private regions = new Map<string, Region>();
  /** Built when first asked after the masks changed (a pointer over the photo), not per edit. */
  private hitMap: HitMap | null = null;
  private colours = new Map<string, Rgb>();
  /** What the arrows and labels were last drawn from. */
  private drawnSupports = "";
  /** Counts mask changes (part of what the arrows and labels depend on). */
  private geometryVersion = 0;
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
    if (!this.hitMap) {
      const { width, height } = this.session.doc.scene.image;
      const placed = this.session.objects.flatMap((object) => {
        const region = this.regions.get(object.id);
        return region ? [{ object, region }] : [];
      });
      this.hitMap = new HitMap(width, height, placed);
    }
    return this.hitMap.at(x, y);
  }

  /**
   * The object whose label tag covers a photo point, or null. Tags are drawn over the masks,
   * and a crowd pushes some off their objects: a click on one means its object.
   */
  labelAt(x: number, y: number): string | null {
    const labels = this.layers.labels;
    if (labels.getClientRects().length === 0) return null; // labels hidden (or none drawn)
    const hit = drawnLabelTags(labels)
      .reverse()
      .find(({ rect }) => x >= rect.left && x <= rect.right && y >= rect.top && y <= rect.bottom);
    return hit?.id || null;
  }

  /** The centre of the object's mask (for arrows drawn to it). */
  centroid(id: string): [number, number] | null {
    return this.regions.get(id)?.centroid ?? null;
  }

  /**
   * The masks, when an object's mask, box or colour changed: only those objects' masks are
   * decoded and encoded again, and the other nodes stay as they are.
   */
  drawGeometry(): void {
    const objects = this.session.objects;
    const { colouring, opacity } = maskStyle.get();
    this.svg.style.setProperty("--mask-opacity", String(opacity));
    const colours = maskColours(objects, colouring, this.session.doc.scene.removed_by_person);
    const drawn = new Map<string, DrawnMask>();
    let changed = objects.length !== this.drawn.size;
    for (const object of objects) {
      const colour = colours.get(object.id) ?? GREY;
      const key = maskKey(object, colour);
      let entry = this.drawn.get(object.id);
      if (entry?.key !== key) {
        const region = objectRegion(object);
        entry = { key, region, node: maskNode(object, region, colour) };
        changed = true;
      }
      drawn.set(object.id, entry);
    }
    this.colours = colours;
    if (!changed && [...drawn.keys()].every((id, i) => objects[i]?.id === id)) return;
    this.drawn = drawn;
    this.regions = new Map([...drawn].map(([id, d]) => [id, d.region]));
    this.hitMap = null;
    this.geometryVersion += 1;
    placeChildren(
      this.layers.masks,
      [...drawn.values()].map((d) => d.node),
    );
  }

  /** The support arrows and the labels (again only when what they show changed). */
  drawSupports(): void {
    const { session, layers, frame, regions, overlayScale } = this;
    const { objects } = session;
    const shown = session.shown();
    const suggested = session.suggestions();
    const key = JSON.stringify([
      this.geometryVersion,
      overlayScale,
      objects.map((o) => [o.id, o.class, o.bbox]),
      [...shown],
      [...suggested],
      [...this.colours],
    ]);
    if (key === this.drawnSupports) return;
    this.drawnSupports = key;
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
    // A selection (a click, N, the list) keeps its own edges in view and fades the rest less
    // than a hover does; the selected arrow is drawn last, over a crowd of others.
    svg.classList.toggle("has-selection", selected !== null);
    for (const node of svg.querySelectorAll<SVGElement>("[data-object], [data-child]")) {
      const id = node.dataset.object ?? node.dataset.child;
      node.classList.toggle("is-hovered", id === hovered);
      node.classList.toggle("is-selected", id === selected);
      // An arrow from the hovered object to what it holds up stays in view too.
      node.classList.toggle("is-related", hovered !== null && node.dataset.parent === hovered);
      node.classList.toggle(
        "is-related-to-selected",
        selected !== null && node.dataset.parent === selected,
      );
    }
    const selectedArrow =
      selected === null
        ? null
        : this.layers.arrows.querySelector<SVGElement>(
            `.arrow[data-child="${CSS.escape(selected)}"]`,
          );
    if (selectedArrow && selectedArrow !== selectedArrow.parentNode?.lastChild)
      selectedArrow.parentNode?.appendChild(selectedArrow);
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
