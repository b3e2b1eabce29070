// Support arrows in the 3D view: a shaft and a head per arrow, drawn as two instanced meshes
// (two draw calls for any number of arrows, which keeps software WebGL fast).
import * as THREE from "three";
import type { Arrow3d } from "./arrowPlan";

const BELOW = new THREE.Color(0xd7261e); // styles.css --below
const BEHIND = new THREE.Color(0x1e5fd9); // styles.css --behind
const SHAFT_RADIUS = 0.018;
const HEAD_RADIUS = 0.055;
const HEAD_LENGTH = 0.14;
const CAPACITY_STEP = 32;

const UP = new THREE.Vector3(0, 1, 0);

export class SupportArrows3d {
  readonly root = new THREE.Group();
  private shafts: THREE.InstancedMesh;
  private heads: THREE.InstancedMesh;
  private readonly shaftGeometry: THREE.CylinderGeometry;
  private readonly headGeometry: THREE.ConeGeometry;
  private readonly material = new THREE.MeshLambertMaterial();
  private shown: Arrow3d[] = [];

  constructor() {
    this.root.name = "support-arrows";
    // Both unit shapes stand on the origin and point up +y; instances stretch and turn them.
    this.shaftGeometry = new THREE.CylinderGeometry(SHAFT_RADIUS, SHAFT_RADIUS, 1, 8);
    this.shaftGeometry.translate(0, 0.5, 0);
    this.headGeometry = new THREE.ConeGeometry(HEAD_RADIUS, HEAD_LENGTH, 14);
    this.headGeometry.translate(0, HEAD_LENGTH / 2, 0);
    [this.shafts, this.heads] = this.allocate(CAPACITY_STEP);
  }

  get count(): number {
    return this.shown.length;
  }

  get arrows(): readonly Arrow3d[] {
    return this.shown;
  }

  set(arrows: readonly Arrow3d[]): void {
    this.shown = [...arrows];
    if (arrows.length > this.shafts.instanceMatrix.count) {
      this.disposeMeshes();
      [this.shafts, this.heads] = this.allocate(
        Math.ceil(arrows.length / CAPACITY_STEP) * CAPACITY_STEP,
      );
    }
    const start = new THREE.Vector3();
    const end = new THREE.Vector3();
    const direction = new THREE.Vector3();
    const turn = new THREE.Quaternion();
    const matrix = new THREE.Matrix4();
    arrows.forEach((arrow, i) => {
      start.fromArray(arrow.start);
      end.fromArray(arrow.end);
      direction.subVectors(end, start);
      const length = direction.length();
      direction.divideScalar(length || 1);
      turn.setFromUnitVectors(UP, direction);
      const shaft = Math.max(length - HEAD_LENGTH, 1e-3);
      matrix.compose(start, turn, new THREE.Vector3(1, shaft, 1));
      this.shafts.setMatrixAt(i, matrix);
      matrix.compose(
        start.clone().addScaledVector(direction, shaft),
        turn,
        new THREE.Vector3(1, 1, 1),
      );
      this.heads.setMatrixAt(i, matrix);
      const colour = arrow.type === "below" ? BELOW : BEHIND;
      this.shafts.setColorAt(i, colour);
      this.heads.setColorAt(i, colour);
    });
    for (const mesh of [this.shafts, this.heads]) {
      mesh.count = arrows.length;
      mesh.instanceMatrix.needsUpdate = true;
      if (mesh.instanceColor) mesh.instanceColor.needsUpdate = true;
      mesh.computeBoundingSphere();
    }
  }

  dispose(): void {
    this.disposeMeshes();
    this.shaftGeometry.dispose();
    this.headGeometry.dispose();
    this.material.dispose();
  }

  private allocate(capacity: number): [THREE.InstancedMesh, THREE.InstancedMesh] {
    const make = (geometry: THREE.BufferGeometry, name: string) => {
      const mesh = new THREE.InstancedMesh(geometry, this.material, capacity);
      mesh.name = name;
      mesh.count = 0;
      mesh.setColorAt(0, BELOW); // creates the colour buffer
      // The arrows are picked through, not picked: clicks go to the objects.
      mesh.raycast = () => {};
      this.root.add(mesh);
      return mesh;
    };
    return [make(this.shaftGeometry, "arrow-shafts"), make(this.headGeometry, "arrow-heads")];
  }

  private disposeMeshes(): void {
    for (const mesh of [this.shafts, this.heads]) {
      this.root.remove(mesh);
      mesh.dispose();
    }
  }
}
