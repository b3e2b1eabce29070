// Object ids over the 3D view, as on the photo: a dark tag with the object's colour over the
// top of each object, so a reviewer can match what is drawn in 3D with the photo and the
// object list without pointing at each one. Where two tags would overlap, the larger object's
// is drawn (a bookshelf's, not one of the ten books on it; the hovered and the selected
// object's always), and the checkbox's tooltip says how many are drawn; clicking a tag
// selects its object.
// The tags are HTML over the canvas, moved after each frame: nothing to draw in WebGL.
import * as THREE from "three";
import { el } from "../../dom";
import type { SceneSession } from "../../state/sceneSession";
import { type Rgb, rgbCss } from "../rgb";
import type { SceneModel } from "./sceneModel";

/** A tag's size on the screen, in CSS pixels: its height, and its width per character of the
 * id plus the swatch and padding (the font is monospace, so this is close enough to place). */
const TAG_HEIGHT = 18;
const TAG_CHAR_WIDTH = 7.5;
const TAG_EXTRA_WIDTH = 22;

export interface LabelCandidate {
  id: string;
  /** Where the tag's bottom centre goes, in pixels of the viewport. */
  x: number;
  y: number;
  /** The larger wins a place (the object's 3D box volume). */
  size: number;
  /** Hovered or selected: placed first, whatever else is there. */
  wanted: boolean;
}

export interface PlacedLabel {
  id: string;
  left: number;
  top: number;
}

/** The tags to draw: wanted ones first, then the largest objects', each left out where it would
 * overlap a tag placed before it or leave the viewport (`width` x `height` pixels). */
export function placeLabels(
  candidates: readonly LabelCandidate[],
  width: number,
  height: number,
): PlacedLabel[] {
  const order = [...candidates].sort(
    (a, b) => Number(b.wanted) - Number(a.wanted) || b.size - a.size,
  );
  const placed: (PlacedLabel & { right: number; bottom: number })[] = [];
  for (const candidate of order) {
    const tagWidth = candidate.id.length * TAG_CHAR_WIDTH + TAG_EXTRA_WIDTH;
    const left = Math.round(candidate.x - tagWidth / 2);
    const top = Math.round(candidate.y - TAG_HEIGHT);
    const right = left + tagWidth;
    const bottom = top + TAG_HEIGHT;
    const inside = left >= 0 && top >= 0 && right <= width && bottom <= height;
    if (!inside && !candidate.wanted) continue;
    const overlaps = placed.some(
      (p) => left < p.right && p.left < right && top < p.bottom && p.top < bottom,
    );
    if (overlaps && !candidate.wanted) continue;
    placed.push({ id: candidate.id, left, top, right, bottom });
  }
  return placed.map(({ id, left, top }) => ({ id, left, top }));
}

export interface ViewportLabelsInputs {
  viewport: HTMLElement;
  /** Where the "Labels" checkbox goes. */
  toolbar: HTMLElement;
  camera: THREE.PerspectiveCamera;
  session: SceneSession;
  /** The objects drawn now (null before the first GLB). */
  model(): SceneModel | null;
  /** The objects' colours, as on the photo. */
  colours(): ReadonlyMap<string, Rgb>;
  requestRender(): void;
}

export class ViewportLabels {
  private readonly layer = el("div", { className: "scene3d-labels", testid: "scene3d-labels" });
  private readonly tags = new Map<string, HTMLElement>();
  /** Each object's tag anchor (the top centre of its meshes' box) and that box's volume, for
   * the model they came from. */
  private anchors = new Map<string, { at: THREE.Vector3; size: number }>();
  private anchoredModel: SceneModel | null = null;
  private shown = true;
  private readonly toggleLabel: HTMLLabelElement;

  constructor(private readonly inputs: ViewportLabelsInputs) {
    const toggle = el("input", {
      testid: "toggle-scene3d-labels",
      attrs: { type: "checkbox", checked: true },
      on: {
        change: () => {
          this.shown = toggle.checked;
          this.layer.hidden = !this.shown;
          inputs.requestRender();
        },
      },
    });
    this.toggleLabel = el(
      "label",
      { className: "toggle", attrs: { title: "Each object's id over it, as on the photo" } },
      toggle,
      "Labels",
    );
    inputs.toolbar.append(this.toggleLabel);
    // A click on a tag selects its object; pointing at it points at the object.
    this.layer.addEventListener("click", (event) => {
      const id = this.tagIdOf(event.target);
      if (id !== null) inputs.session.select(id);
    });
    this.layer.addEventListener("pointerover", (event) => {
      const id = this.tagIdOf(event.target);
      if (id !== null) inputs.session.hover(id);
    });
    this.layer.addEventListener("pointerout", (event) => {
      if (this.tagIdOf(event.target) !== null) inputs.session.hover(null);
    });
    inputs.viewport.append(this.layer);
  }

  private tagIdOf(target: EventTarget | null): string | null {
    const tag = target instanceof Element ? target.closest<HTMLElement>("[data-object]") : null;
    return tag?.dataset.object ?? null;
  }

  /** Move the tags to where the last frame drew their objects. */
  update(): void {
    const model = this.inputs.model();
    if (!this.shown || !model) {
      for (const tag of this.tags.values()) tag.hidden = true;
      return;
    }
    if (model !== this.anchoredModel) this.anchor(model);
    const { camera, session, viewport } = this.inputs;
    const width = viewport.clientWidth;
    const height = viewport.clientHeight;
    camera.updateMatrixWorld();
    const point = new THREE.Vector3();
    const candidates: LabelCandidate[] = [];
    const present = new Set(session.objects.map((o) => o.id));
    for (const [id, { at, size }] of this.anchors) {
      if (!present.has(id)) continue; // removed in an edit since this GLB
      point.copy(at).project(camera);
      if (point.z > 1 || point.z < -1) continue; // behind the camera or past its far plane
      candidates.push({
        id,
        x: ((point.x + 1) / 2) * width,
        y: ((1 - point.y) / 2) * height,
        size,
        wanted: id === session.selected || id === session.hovered,
      });
    }
    const placed = new Map(placeLabels(candidates, width, height).map((p) => [p.id, p]));
    const title = `Each object's id over it, as on the photo: ${placed.size} of ${this.anchors.size} drawn where they do not overlap (larger objects first); point at an object for its id`;
    if (this.toggleLabel.title !== title) this.toggleLabel.title = title;
    const colours = this.inputs.colours();
    for (const id of new Set([...this.tags.keys(), ...placed.keys()])) {
      const spot = placed.get(id);
      const tag = this.tags.get(id) ?? (spot ? this.makeTag(id) : undefined);
      if (!tag) continue;
      tag.hidden = !spot;
      if (!spot) continue;
      tag.style.transform = `translate(${spot.left}px, ${spot.top}px)`;
      tag.classList.toggle("is-selected", id === session.selected);
      tag.classList.toggle("is-hovered", id === session.hovered);
      // Written only when it changes: this runs on every frame of an orbit.
      const colour = colours.get(id);
      const css = colour ? rgbCss(colour) : "transparent";
      if (tag.dataset.colour !== css) {
        tag.dataset.colour = css;
        (tag.firstElementChild as HTMLElement).style.background = css;
      }
    }
  }

  private anchor(model: SceneModel): void {
    this.anchors = new Map();
    this.anchoredModel = model;
    model.root.updateWorldMatrix(true, true);
    for (const object of this.inputs.session.objects) {
      const box = new THREE.Box3();
      for (const mesh of model.meshesOf(object.id)) box.expandByObject(mesh);
      if (box.isEmpty()) continue; // not placed in 3D
      const centre = box.getCenter(new THREE.Vector3());
      const extent = box.getSize(new THREE.Vector3());
      this.anchors.set(object.id, {
        at: new THREE.Vector3(centre.x, box.max.y, centre.z),
        size: extent.x * extent.y * extent.z,
      });
    }
  }

  private makeTag(id: string): HTMLElement {
    const tag = el(
      "span",
      {
        className: "scene3d-label",
        testid: `scene3d-label-${id}`,
        attrs: { "data-object": id },
      },
      el("span", { className: "scene3d-label-swatch" }),
      id,
    );
    this.tags.set(id, tag);
    this.layer.append(tag);
    return tag;
  }

  dispose(): void {
    this.layer.remove();
  }
}
