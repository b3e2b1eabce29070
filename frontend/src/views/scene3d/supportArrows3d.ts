// Support arrows in the 3D view: a shaft and a head per arrow, all baked into one mesh
// and lit once (bakedMesh.ts: one draw call for any number of arrows and no lighting per
// pixel, which keeps software WebGL fast). Rebuilt when the arrows change.
import * as THREE from "three";
import type { Arrow3d } from "./arrowPlan";
import { BakedGeometry, type BakedPart } from "./bakedMesh";

const BELOW = new THREE.Color(0xd7261e); // styles.css --below
const BEHIND = new THREE.Color(0x1e5fd9); // styles.css --behind
const SHAFT_RADIUS = 0.018;
const HEAD_RADIUS = 0.055;
const HEAD_LENGTH = 0.14;

const UP = new THREE.Vector3(0, 1, 0);

export class SupportArrows3d {
  readonly root = new THREE.Group();
  private readonly mesh: THREE.Mesh;
  private readonly shaftGeometry: THREE.CylinderGeometry;
  private readonly headGeometry: THREE.ConeGeometry;
  /** Lit once, when baked: see bakedMesh.ts. */
  private readonly material = new THREE.MeshBasicMaterial({ vertexColors: true });
  private shown: Arrow3d[] = [];

  constructor() {
    this.root.name = "support-arrows";
    // Both unit shapes stand on the origin and point up +y; each arrow stretches and turns them.
    // Few sides (a shaft is a few pixels wide) and an open shaft (its ends are inside the
    // head and the supporter): software WebGL pays per triangle.
    this.shaftGeometry = new THREE.CylinderGeometry(SHAFT_RADIUS, SHAFT_RADIUS, 1, 6, 1, true);
    this.shaftGeometry.translate(0, 0.5, 0);
    this.headGeometry = new THREE.ConeGeometry(HEAD_RADIUS, HEAD_LENGTH, 10);
    this.headGeometry.translate(0, HEAD_LENGTH / 2, 0);
    this.mesh = new THREE.Mesh(new THREE.BufferGeometry(), this.material);
    this.mesh.name = "arrows";
    this.mesh.matrixAutoUpdate = false;
    this.mesh.visible = false;
    // The arrows are picked through, not picked: clicks go to the objects.
    this.mesh.raycast = () => {};
    this.root.add(this.mesh);
  }

  get count(): number {
    return this.shown.length;
  }

  get arrows(): readonly Arrow3d[] {
    return this.shown;
  }

  /** Show these arrows; the same arrows again (the view redraws on many changes) keep the
   * baked mesh. */
  set(arrows: readonly Arrow3d[]): void {
    if (sameArrows(arrows, this.shown)) return;
    this.shown = [...arrows];
    const start = new THREE.Vector3();
    const end = new THREE.Vector3();
    const direction = new THREE.Vector3();
    const turn = new THREE.Quaternion();
    const parts: BakedPart[] = [];
    for (const arrow of arrows) {
      start.fromArray(arrow.start);
      end.fromArray(arrow.end);
      direction.subVectors(end, start);
      const length = direction.length();
      direction.divideScalar(length || 1);
      turn.setFromUnitVectors(UP, direction);
      const shaft = Math.max(length - HEAD_LENGTH, 1e-3);
      const colour = arrow.type === "below" ? BELOW : BEHIND;
      parts.push(
        {
          geometry: this.shaftGeometry,
          matrix: new THREE.Matrix4().compose(start, turn, new THREE.Vector3(1, shaft, 1)),
          colour,
        },
        {
          geometry: this.headGeometry,
          matrix: new THREE.Matrix4().compose(
            start.clone().addScaledVector(direction, shaft),
            turn,
            new THREE.Vector3(1, 1, 1),
          ),
          colour,
        },
      );
    }
    this.mesh.geometry.dispose();
    this.mesh.geometry = new BakedGeometry(parts).geometry;
    this.mesh.visible = parts.length > 0;
  }

  dispose(): void {
    this.mesh.geometry.dispose();
    this.shaftGeometry.dispose();
    this.headGeometry.dispose();
    this.material.dispose();
  }
}

const sameCoords = (a: readonly number[], b: readonly number[]) =>
  a.length === b.length && a.every((v, k) => v === b[k]);

function sameArrows(a: readonly Arrow3d[], b: readonly Arrow3d[]): boolean {
  return (
    a.length === b.length &&
    a.every((x, i) => {
      const y = b[i];
      return (
        y !== undefined &&
        x.child === y.child &&
        x.parent === y.parent &&
        x.type === y.type &&
        sameCoords(x.start, y.start) &&
        sameCoords(x.end, y.end)
      );
    })
  );
}
