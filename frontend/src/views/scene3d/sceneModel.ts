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
  private readonly materials = new Map<string, THREE.MeshStandardMaterial>();

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
      disposeMaterial(node.material);
      node.material = material;
    });
  }

  /** Parse GLB bytes; meshes named by object id take their class colour. */
  static async parse(bytes: ArrayBuffer, objects: readonly SceneObject[]): Promise<SceneModel> {
    const gltf = await new GLTFLoader().parseAsync(bytes, "");
    return new SceneModel(gltf.scene, objects);
  }

  /** The object id a mesh belongs to: the nearest node named by an object id (or "floor"). */
  private static idOf(node: THREE.Object3D, classOf: ReadonlyMap<string, string>): string | null {
    for (let at: THREE.Object3D | null = node; at; at = at.parent) {
      if (classOf.has(at.name) || at.name === "floor") return at.name;
    }
    return null;
  }

  private materialFor(id: string, colour: number): THREE.MeshStandardMaterial {
    let material = this.materials.get(id);
    if (!material) {
      material = new THREE.MeshStandardMaterial({
        color: colour,
        roughness: 0.75,
        metalness: 0,
        side: THREE.DoubleSide,
      });
      this.materials.set(id, material);
    }
    return material;
  }

  /** Make the given objects glow; all others plain. */
  highlight(ids: ReadonlySet<string>): void {
    for (const [id, material] of this.materials) {
      material.emissive.copy(ids.has(id) ? HIGHLIGHT : NO_GLOW);
    }
  }

  /** Box around the objects (the floor left out, as it may extend far). */
  objectBounds(): THREE.Box3 {
    const box = new THREE.Box3();
    this.root.updateWorldMatrix(true, true);
    this.root.traverse((node) => {
      if (node instanceof THREE.Mesh && node.userData.objectId !== "floor")
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

function disposeMaterial(material: THREE.Material | THREE.Material[]): void {
  for (const m of Array.isArray(material) ? material : [material]) m.dispose();
}
