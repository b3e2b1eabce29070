// What follows the layout editor live, without waiting for a saved revision: the room box, the
// photo's camera frustum (the photo on its image plane) and the support arrows.
import type * as THREE from "three";
import { type LayoutDraft, type LiveRoom, storedRoom } from "../../state/layoutDraft";
import type { SceneSession } from "../../state/sceneSession";
import { planArrows } from "./arrowPlan";
import { PhotoFrustum } from "./photoFrustum";
import { RoomMesh } from "./roomMesh";
import { SupportArrows3d } from "./supportArrows3d";

/** Distance of the frustum's image plane from the camera centre, metres. */
const FRUSTUM_DEPTH = 0.4;

export class LiveLayers {
  readonly room = new RoomMesh();
  readonly arrows = new SupportArrows3d();
  frustum: PhotoFrustum | null = null;
  /** The camera matrix the frustum was built for (JSON): a new one builds it again. */
  private frustumK = "";
  /** Whether the photo lets what is behind it show through (kept for a new frustum). */
  private photoSeeThrough = false;

  constructor(
    private readonly scene: THREE.Scene,
    private readonly requestRender: () => void,
  ) {
    scene.add(this.room.root, this.arrows.root);
  }

  /**
   * Draw the room, frustum and arrows of the session's revision and the layout draft (if any);
   * `photoUrl` is the photo shown on the frustum. Returns the room drawn (null: none).
   */
  show(session: SceneSession, layout: LayoutDraft | null, photoUrl: string): LiveRoom | null {
    const doc = session.doc;
    const live = layout ? layout.live : storedRoom(doc);
    this.room.set(live?.room ?? null);
    this.room.setEditing(layout?.editing ?? false);
    const K = doc.scene.camera?.K;
    const key = JSON.stringify(K ?? null);
    if (key !== this.frustumK) {
      this.frustumK = key;
      if (this.frustum) {
        this.scene.remove(this.frustum.root);
        this.frustum.dispose();
        this.frustum = null;
      }
      if (K) {
        const { width, height } = doc.scene.image;
        this.frustum = new PhotoFrustum(K, width, height, FRUSTUM_DEPTH);
        this.frustum.loadPhoto(photoUrl, this.requestRender);
        this.frustum.setSeeThrough(this.photoSeeThrough);
        this.scene.add(this.frustum.root);
      }
    }
    // Without pitch and roll the frustum is drawn level (as the reviewer viewer does).
    this.frustum?.setPose(live?.pitchDeg ?? 0, live?.rollDeg ?? 0);
    const floorY = doc.scene.camera?.height_m != null ? -doc.scene.camera.height_m : null;
    this.arrows.set(
      planArrows(session.objects, session.shown().values(), {
        corners: live?.corners3d ?? null,
        floorY,
      }),
    );
    this.requestRender();
    return live;
  }

  /** Let what lies behind the photo on the frustum show through it, or not. */
  setPhotoSeeThrough(on: boolean): void {
    this.photoSeeThrough = on;
    this.frustum?.setSeeThrough(on);
    this.requestRender();
  }

  /** Whether the frustum is in the scene now. */
  get frustumShown(): boolean {
    return this.frustum !== null && this.frustum.root.parent === this.scene;
  }

  dispose(): void {
    this.room.dispose();
    this.arrows.dispose();
    this.frustum?.dispose();
  }
}
