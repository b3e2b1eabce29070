// The photo's camera in the 3D view: a frustum from the camera centre (the world origin) to an
// image plane carrying the photo. The shape comes from K in OpenCV camera coordinates (x right,
// y down, z forward); the camera's pitch and roll turn it into the world (camera.ts
// worldFromCv), so a layout drag that changes them only turns the frustum.
import * as THREE from "three";
import { invert, type Matrix3Like, matVec, worldFromCv } from "../../geometry/camera";

const LINE = 0x1d2430;
// See-through enough that an object close in front of the camera still shows behind the photo.
const OPACITY = 0.75;
/** While the depth points are shown: from the photo's viewpoint they lie behind the photo. */
const SEE_THROUGH_OPACITY = 0.35;

export class PhotoFrustum {
  readonly root = new THREE.Group();
  private readonly lines: THREE.LineSegments;
  private readonly plane: THREE.Mesh;
  private readonly lineMaterial = new THREE.LineBasicMaterial({ color: LINE });
  private readonly planeMaterial: THREE.MeshBasicMaterial;
  private texture: THREE.Texture | null = null;
  private pose: { pitchDeg: number; rollDeg: number } = { pitchDeg: 0, rollDeg: 0 };

  /** `depth`: distance of the image plane from the camera centre, metres. */
  constructor(K: Matrix3Like, width: number, height: number, depth: number) {
    this.root.name = "photo-frustum";
    this.root.matrixAutoUpdate = false;
    const kInverse = invert(K);
    const corner = (u: number, v: number) => {
      const ray = matVec(kInverse, [u, v, 1]); // z = 1: scaled to the plane's depth
      return new THREE.Vector3(ray[0], ray[1], ray[2]).multiplyScalar(depth / ray[2]);
    };
    // Top-left, top-right, bottom-right, bottom-left, as the photo's pixels.
    const quad = [corner(0, 0), corner(width, 0), corner(width, height), corner(0, height)];
    const origin = new THREE.Vector3();
    const segments = quad.flatMap((p, i) => [origin, p, p, quad[(i + 1) % 4] as THREE.Vector3]);
    this.lines = new THREE.LineSegments(
      new THREE.BufferGeometry().setFromPoints(segments),
      this.lineMaterial,
    );
    const planeGeometry = new THREE.BufferGeometry().setFromPoints(quad);
    planeGeometry.setAttribute("uv", new THREE.Float32BufferAttribute([0, 1, 1, 1, 1, 0, 0, 0], 2));
    planeGeometry.setIndex([0, 2, 1, 0, 3, 2]);
    this.planeMaterial = new THREE.MeshBasicMaterial({
      color: 0xbfc5cc,
      side: THREE.DoubleSide,
      transparent: true,
      opacity: OPACITY,
      forceSinglePass: true, // one flat quad: one draw call, not one per side
    });
    this.plane = new THREE.Mesh(planeGeometry, this.planeMaterial);
    this.plane.name = "photo-plane";
    this.plane.raycast = () => {}; // clicks pass through to the room and objects
    this.lines.raycast = () => {};
    this.root.add(this.lines, this.plane);
  }

  /** Show the photo on the image plane; `onLoad` is called once it is there. */
  loadPhoto(url: string, onLoad: () => void): void {
    new THREE.TextureLoader().load(url, (texture) => {
      texture.colorSpace = THREE.SRGBColorSpace;
      this.texture?.dispose();
      this.texture = texture;
      this.planeMaterial.map = texture;
      this.planeMaterial.color.set(0xffffff);
      this.planeMaterial.needsUpdate = true;
      onLoad();
    });
  }

  /** Let what lies behind the photo show through it (the depth points), or not. */
  setSeeThrough(on: boolean): void {
    this.planeMaterial.opacity = on ? SEE_THROUGH_OPACITY : OPACITY;
  }

  get hasPhoto(): boolean {
    return this.texture !== null;
  }

  get pitchRoll(): { pitchDeg: number; rollDeg: number } {
    return { ...this.pose };
  }

  /** Turn the frustum to the camera's pitch and roll (degrees). */
  setPose(pitchDeg: number, rollDeg: number): void {
    this.pose = { pitchDeg, rollDeg };
    const r = worldFromCv(pitchDeg, rollDeg);
    this.root.matrix.set(
      r[0][0],
      r[0][1],
      r[0][2],
      0,
      r[1][0],
      r[1][1],
      r[1][2],
      0,
      r[2][0],
      r[2][1],
      r[2][2],
      0,
      0,
      0,
      0,
      1,
    );
    this.root.matrixWorldNeedsUpdate = true;
  }

  dispose(): void {
    this.lines.geometry.dispose();
    this.plane.geometry.dispose();
    this.lineMaterial.dispose();
    this.planeMaterial.dispose();
    this.texture?.dispose();
  }
}
