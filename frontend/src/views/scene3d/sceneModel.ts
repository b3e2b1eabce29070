// The GLB scene as loaded for display: meshes coloured by class, found by object id.
import type { SceneObject } from "@holiscene/schema";
import * as THREE from "three";
import { GLTFLoader } from "three/examples/jsm/loaders/GLTFLoader.js";
import { classHex } from "../classColors";

const FLOOR_COLOUR = 0xb9b4aa;
const HIGHLIGHT = new THREE.Color(0x555555);
const NO_GLOW = new THREE.Color(0x000000);

export class SceneModel {
  readonly root: THREE.Object3D;
  private readonly materials = new Map<string, THREE.MeshLambertMaterial>();

  private constructor(root: THREE.Object3D, objects: readonly SceneObject[]) {
    this.root = root;
    const classOf = new Map(objects.map((o) => [o.id, o.class]));
    root.traverse((node) => {
      if (!(node instanceof THREE.Mesh)) return;
      const id = SceneModel.idOf(node, classOf);
      if (id === null) return;
      node.userData.objectId = id;
      const cls = classOf.get(id);
      const material = this.materialFor(id, cls === undefined ? FLOOR_COLOUR : classHex(cls));
      // Room surfaces face inwards and are drawn one-sided: from outside, the walls between
      // the viewer and the room disappear (a dollhouse view); from the photo's viewpoint
      // they all show.
      if (cls === undefined) material.side = THREE.FrontSide;
      disposeMaterial(node.material);
      node.material = material;
    });
  }

  /** Parse GLB bytes; meshes named by object id take their class colour. */
  static async parse(bytes: ArrayBuffer, objects: readonly SceneObject[]): Promise<SceneModel> {
    const gltf = await new GLTFLoader().parseAsync(bytes, "");
    return new SceneModel(gltf.scene, objects);
  }

  /** The object id a mesh belongs to: the nearest node named by an object id (or a room surface). */
  private static idOf(node: THREE.Object3D, classOf: ReadonlyMap<string, string>): string | null {
    for (let at: THREE.Object3D | null = node; at; at = at.parent) {
      if (classOf.has(at.name) || isRoomSurface(at.name)) return at.name;
    }
    return null;
  }

  private materialFor(id: string, colour: number): THREE.MeshLambertMaterial {
    let material = this.materials.get(id);
    if (!material) {
      // Diffuse only: matte furniture looks as it would with PBR materials, at a fraction of
      // the cost per pixel, which software WebGL feels.
      material = new THREE.MeshLambertMaterial({
        color: colour,
        side: THREE.DoubleSide,
      });
      this.materials.set(id, material);
    }
    return material;
  }

  /** Show or hide the GLB's own room (the view draws the layout's room itself when known). */
  setRoomVisible(visible: boolean): void {
    this.root.traverse((node) => {
      if (node instanceof THREE.Mesh && isRoomSurface(String(node.userData.objectId)))
        node.visible = visible;
    });
  }

  /** The mesh nodes of an object (empty for an unknown id). */
  meshesOf(id: string): THREE.Mesh[] {
    const meshes: THREE.Mesh[] = [];
    this.root.traverse((node) => {
      if (node instanceof THREE.Mesh && node.userData.objectId === id) meshes.push(node);
    });
    return meshes;
  }

  /** Make the given objects glow; all others plain. */
  highlight(ids: ReadonlySet<string>): void {
    for (const [id, material] of this.materials) {
      material.emissive.copy(ids.has(id) ? HIGHLIGHT : NO_GLOW);
    }
  }

  /** Box around the objects (room surfaces left out, as they may extend far). */
  objectBounds(): THREE.Box3 {
    const box = new THREE.Box3();
    this.root.updateWorldMatrix(true, true);
    this.root.traverse((node) => {
      if (node instanceof THREE.Mesh && !isRoomSurface(String(node.userData.objectId)))
        box.expandByObject(node);
    });
    return box.isEmpty() ? new THREE.Box3().setFromObject(this.root) : box;
  }

  dispose(): void {
    this.root.traverse((node) => {
      if (node instanceof THREE.Mesh) {
        node.geometry.dispose();
        disposeMaterial(node.material);
      }
    });
  }
}

/** GLB nodes of the room itself (see backend export/glb.py): floor, ceiling, wall_0..wall_3. */
export function isRoomSurface(name: string): boolean {
  return name === "floor" || name === "ceiling" || /^wall_\d+$/.test(name);
}

function disposeMaterial(material: THREE.Material | THREE.Material[]): void {
  for (const m of Array.isArray(material) ? material : [material]) m.dispose();
}
