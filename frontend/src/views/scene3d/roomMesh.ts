// The room in the 3D view, drawn from the layout (stored, or being dragged) rather than from
// scene.glb, so it follows the layout editor live. A unit box seen from inside (back faces):
// from outside, the walls facing the viewer disappear (a dollhouse view), from the photo's
// viewpoint they all show. Moving the room is setting the box's position, yaw and scale.
import * as THREE from "three";
import { BOX_CORNER_SIGNS } from "../../geometry/boxes";
import type { RoomBox } from "../../geometry/roomFit";

// Flat shades rather than lit materials: each surface is a plane, which the scene's lights
// (hemisphere and sun, no point lights) would light evenly anyway; unlit, the room, which
// covers most of the view, costs software WebGL little to draw. Walls along the room's two
// axes differ a little so its corners read. One draw call: the faces' shades are vertex
// colours, not six materials (software WebGL pays per draw call).
const WALL_X = 0xd6d1c9;
const WALL_Z = 0xcac5bd;
const FLOOR = 0xb4afa5;
const CEILING = 0xe6e6e4;
const EDGE = 0x6b7280;
const EDGE_EDITING = 0xe0b400;

export class RoomMesh {
  readonly root = new THREE.Group();
  private readonly box: THREE.Mesh;
  private readonly edges: THREE.LineSegments;
  private readonly material = new THREE.MeshBasicMaterial({
    vertexColors: true,
    side: THREE.BackSide,
  });
  private readonly edgeMaterial = new THREE.LineBasicMaterial({ color: EDGE });
  private current: RoomBox | null = null;

  constructor() {
    this.root.name = "room";
    const geometry = new THREE.BoxGeometry(1, 1, 1);
    // BoxGeometry's faces, four vertices each: +x, -x, +y (ceiling), -y (floor), +z, -z.
    const colours = [WALL_X, WALL_X, CEILING, FLOOR, WALL_Z, WALL_Z].flatMap((hex) => {
      const rgb = new THREE.Color(hex).toArray();
      return [...rgb, ...rgb, ...rgb, ...rgb];
    });
    geometry.setAttribute("color", new THREE.Float32BufferAttribute(colours, 3));
    geometry.clearGroups();
    this.box = new THREE.Mesh(geometry, this.material);
    this.box.name = "room-box";
    this.edges = new THREE.LineSegments(new THREE.EdgesGeometry(geometry), this.edgeMaterial);
    this.root.add(this.box, this.edges);
    this.root.visible = false;
  }

  /** The room shown (null: none). */
  get room(): RoomBox | null {
    return this.current;
  }

  set(room: RoomBox | null): void {
    this.current = room;
    this.root.visible = room !== null;
    if (!room) return;
    for (const part of [this.box, this.edges]) {
      part.position.fromArray(room.center);
      part.rotation.set(0, THREE.MathUtils.degToRad(room.yawDeg), 0);
      part.scale.fromArray(room.size);
    }
  }

  /** Edges stand out while the layout is being edited. */
  setEditing(on: boolean): void {
    this.edgeMaterial.color.set(on ? EDGE_EDITING : EDGE);
  }

  /** The room's 8 corners in world coordinates as drawn (for tests and checks). */
  corners(): number[][] {
    this.box.updateWorldMatrix(true, false);
    return BOX_CORNER_SIGNS.map((s) =>
      new THREE.Vector3(s[0] / 2, s[1] / 2, s[2] / 2).applyMatrix4(this.box.matrixWorld).toArray(),
    );
  }

  dispose(): void {
    this.box.geometry.dispose();
    this.edges.geometry.dispose();
    this.material.dispose();
    this.edgeMaterial.dispose();
  }
}
