// The 3D view's camera and its orbit controls: where the view starts (above and behind the
// photo's camera, every object in view), the photo's own viewpoint, and the sphere both frame.
import type { Camera } from "@holiscene/schema";
import * as THREE from "three";
import { OrbitControls } from "three/examples/jsm/controls/OrbitControls.js";

/** The photo camera's vertical field of view in degrees (55 when K is unknown). */
function verticalFov(camera: Camera | null | undefined, imageHeight: number): number {
  const fy = camera?.K[1][1];
  return fy ? THREE.MathUtils.radToDeg(2 * Math.atan(imageHeight / 2 / fy)) : 55;
}

export class ViewportCamera {
  readonly camera: THREE.PerspectiveCamera;
  readonly controls: OrbitControls;
  /** What the overview frames: the objects (or the room), once known. */
  private focus = new THREE.Sphere(new THREE.Vector3(3, 0, 0), 2);

  /** `requestRender` is asked for a frame after each move. */
  constructor(
    canvas: HTMLCanvasElement,
    photoCamera: Camera | null | undefined,
    imageHeight: number,
    private readonly requestRender: () => void,
  ) {
    this.camera = new THREE.PerspectiveCamera(verticalFov(photoCamera, imageHeight), 1, 0.05, 200);
    this.controls = new OrbitControls(this.camera, canvas);
    this.controls.enableDamping = false;
  }

  /** Frame these bounds from now on (kept as they were when empty). */
  fitFocus(bounds: THREE.Box3): void {
    if (!bounds.isEmpty()) this.focus = bounds.getBoundingSphere(new THREE.Sphere());
  }

  /** Look at the objects from above and behind the photo's camera, all in view. */
  readonly overview = (): void => {
    const { camera, controls, focus } = this;
    const centre = focus.center;
    const back = new THREE.Vector3(-centre.x, 0, -centre.z);
    if (back.lengthSq() < 1e-6) back.set(-1, 0, 0);
    const elevation = THREE.MathUtils.degToRad(35);
    const direction = back
      .normalize()
      .multiplyScalar(Math.cos(elevation))
      .setY(Math.sin(elevation));
    const vertical = THREE.MathUtils.degToRad(camera.fov);
    const horizontal = 2 * Math.atan(Math.tan(vertical / 2) * camera.aspect);
    const distance = (focus.radius / Math.sin(Math.min(vertical, horizontal) / 2)) * 1.05;
    camera.position.copy(centre).addScaledVector(direction, distance);
    controls.target.copy(centre);
    controls.update();
    this.requestRender();
  };

  /** Stand at the photo's camera (the origin), looking down by its pitch (degrees). */
  photoView(pitchDeg: number): void {
    const pitch = THREE.MathUtils.degToRad(pitchDeg);
    const distance = Math.max(1, this.focus.center.length());
    this.camera.position.set(0, 0, 0);
    this.controls.target.set(distance * Math.cos(pitch), -distance * Math.sin(pitch), 0);
    this.controls.update();
    this.requestRender();
  }

  /** Turn the view about the orbit target, as a horizontal drag does (radians). */
  orbit(azimuth: number): void {
    const { camera, controls } = this;
    const offset = camera.position.clone().sub(controls.target);
    offset.applyAxisAngle(new THREE.Vector3(0, 1, 0), azimuth);
    camera.position.copy(controls.target).add(offset);
    controls.update(); // its "change" event asks for a frame
  }

  dispose(): void {
    this.controls.dispose();
  }
}
