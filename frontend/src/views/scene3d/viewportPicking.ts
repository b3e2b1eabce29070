// Hover and click in 3D pick objects, as on the photo; and the reverse, for tests: a point on
// the canvas where a click would pick a given object.
import * as THREE from "three";
import type { SceneSession } from "../../state/sceneSession";
import { isRoomSurface, type SceneModel } from "./sceneModel";

/** A press that moves less than this (pixels) before release is a click, not an orbit. */
const CLICK_SLOP = 5;

export class ViewportPicking {
  private readonly raycaster = new THREE.Raycaster();

  /** `model` gives the objects drawn now (null before the first GLB). */
  constructor(
    private readonly canvas: HTMLCanvasElement,
    private readonly camera: THREE.Camera,
    private readonly model: () => SceneModel | null,
  ) {}

  /** The object under a client point (the room's surfaces do not count), or null. */
  objectAt(clientX: number, clientY: number): string | null {
    const model = this.model();
    if (!model) return null;
    const rect = this.canvas.getBoundingClientRect();
    const ndc = new THREE.Vector2(
      ((clientX - rect.left) / rect.width) * 2 - 1,
      -((clientY - rect.top) / rect.height) * 2 + 1,
    );
    this.camera.updateMatrixWorld(); // moved by the controls since the last frame, maybe
    this.raycaster.setFromCamera(ndc, this.camera);
    for (const hit of this.raycaster.intersectObject(model.root, true)) {
      if (!hit.object.visible) continue;
      const id: unknown = hit.object.userData.objectId;
      if (typeof id === "string" && !isRoomSurface(id)) return id;
    }
    return null;
  }

  /** A client point where a click hits the object (not hidden by another), or null. */
  screenPointOf(id: string): { x: number; y: number } | null {
    const model = this.model();
    if (!model) return null;
    const box = new THREE.Box3();
    for (const mesh of model.meshesOf(id)) box.expandByObject(mesh);
    if (box.isEmpty()) return null;
    const rect = this.canvas.getBoundingClientRect();
    const point = new THREE.Vector3();
    this.camera.updateMatrixWorld();
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
          const ndc = point.clone().project(this.camera);
          if (Math.abs(ndc.x) > 0.95 || Math.abs(ndc.y) > 0.95 || ndc.z > 1) continue;
          const x = rect.left + ((ndc.x + 1) / 2) * rect.width;
          const y = rect.top + ((1 - ndc.y) / 2) * rect.height;
          if (this.objectAt(x, y) === id) return { x, y };
        }
      }
    }
    return null;
  }

  /** Hover and select on the session as the pointer moves over and clicks the canvas. */
  listen(session: SceneSession): void {
    const { canvas } = this;
    let pressed: { x: number; y: number } | null = null;
    canvas.addEventListener("pointerdown", (event) => {
      pressed = event.button === 0 ? { x: event.clientX, y: event.clientY } : null;
    });
    canvas.addEventListener("pointerup", (event) => {
      if (!pressed || event.button !== 0) return;
      const moved = Math.hypot(event.clientX - pressed.x, event.clientY - pressed.y);
      pressed = null;
      if (moved > CLICK_SLOP) return; // an orbit, not a click
      // As on the photo: a click on the selected object deselects it.
      const hit = this.objectAt(event.clientX, event.clientY);
      session.select(hit !== null && hit === session.selected ? null : hit);
    });
    canvas.addEventListener("pointermove", (event) => {
      if (event.buttons === 0) session.hover(this.objectAt(event.clientX, event.clientY));
    });
    canvas.addEventListener("pointerleave", () => session.hover(null));
  }
}
