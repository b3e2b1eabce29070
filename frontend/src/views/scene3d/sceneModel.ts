// The GLB scene as loaded for display: meshes coloured as the photo's masks (by object or by
// class, objectColors.ts), found by object id. What is
// drawn is baked (bakedMesh.ts): the objects lit once and merged, closed solids into one mesh
// drawn one-sided and the rest into one drawn two-sided, and the GLB's room surfaces as a
// third; the GLB's own nodes stay, undrawn, for picking and bounds.
import type { SceneObject } from "@holiscene/schema";
import * as THREE from "three";
import { GLTFLoader } from "three/examples/jsm/loaders/GLTFLoader.js";
import { classColours } from "../objectColors";
import { type Rgb, rgbHex } from "../rgb";
import { BakedGeometry, type BakedPart, solidWinding } from "./bakedMesh";

const FLOOR_COLOUR = 0xb9b4aa;
/** The objects' opacity while drawn see-through (the depth points shown). */
const SEE_THROUGH_OPACITY = 0.3;
/** What a selected or hovered object emits on top of its lit colour (it glows). In linear
 * light: 0x555555 added only 0.09 per channel, too faint to find one chair among 30. */
const HIGHLIGHT = new THREE.Color(0x8a8a8a);

export class SceneModel {
  /** The GLB's nodes, meshes tagged with their object id: picked and measured, not drawn. */
  readonly root: THREE.Object3D;
  /** What the view draws: the objects (solids, others) and the GLB's room surfaces. */
  readonly view = new THREE.Group();
  private readonly solids: BakedGeometry;
  private readonly others: BakedGeometry;
  private readonly room: BakedGeometry;
  private readonly roomMesh: THREE.Mesh;
  /** Objects are drawn two-sided, but for closed solids, whose back faces never show; room
   * surfaces face inwards and are drawn one-sided: from outside, the walls between the
   * viewer and the room disappear (a dollhouse view); from the photo's viewpoint they all
   * show. Picking sees the objects' faces from both sides, the room's as drawn. */
  private readonly materials = {
    solids: new THREE.MeshBasicMaterial({ vertexColors: true, side: THREE.FrontSide }),
    others: new THREE.MeshBasicMaterial({ vertexColors: true, side: THREE.DoubleSide }),
    room: new THREE.MeshBasicMaterial({ vertexColors: true, side: THREE.FrontSide }),
    pickObject: new THREE.MeshBasicMaterial({ side: THREE.DoubleSide }),
    pickRoom: new THREE.MeshBasicMaterial({ side: THREE.FrontSide }),
  };
  /** Object id -> its parts in the baked objects, with their colours. */
  private readonly partsOf = new Map<
    string,
    { baked: "solids" | "others"; part: number; colour: THREE.Color }[]
  >();
  private readonly roomNodes: THREE.Mesh[] = [];
  private lit = new Set<string>();

  private constructor(
    root: THREE.Object3D,
    objects: readonly SceneObject[],
    colours: ReadonlyMap<string, Rgb>,
  ) {
    this.root = root;
    root.updateMatrixWorld(true); // not in the drawn scene: nothing else updates it
    const classOf = new Map(objects.map((o) => [o.id, o.class]));
    const objectParts = { solids: [] as BakedPart[], others: [] as BakedPart[] };
    const roomParts: BakedPart[] = [];
    root.traverse((node) => {
      if (!(node instanceof THREE.Mesh)) return;
      const id = SceneModel.idOf(node, classOf);
      const cls = id === null ? undefined : classOf.get(id);
      const glbMaterial = node.material;
      const part = { geometry: node.geometry, matrix: node.matrixWorld };
      if (id !== null) node.userData.objectId = id;
      if (id !== null && cls === undefined) {
        roomParts.push({ ...part, colour: new THREE.Color(FLOOR_COLOUR) });
        this.roomNodes.push(node);
        node.material = this.materials.pickRoom;
      } else {
        // A mesh of no object (none in the pipeline's GLB) keeps its own colour.
        const own = Array.isArray(glbMaterial) ? undefined : glbColour(glbMaterial);
        const given = id === null ? undefined : colours.get(id);
        const colour =
          cls !== undefined
            ? new THREE.Color(rgbHex(given ?? classColours([cls]).get(cls) ?? [128, 128, 128]))
            : (own ?? new THREE.Color(FLOOR_COLOUR));
        const winding = solidWinding(node.geometry, node.matrixWorld);
        const baked = winding === 0 ? "others" : "solids";
        if (id !== null) {
          const entry = { baked, part: objectParts[baked].length, colour } as const;
          this.partsOf.set(id, [...(this.partsOf.get(id) ?? []), entry]);
        }
        objectParts[baked].push({ ...part, colour, flip: winding === -1 });
        node.material = this.materials.pickObject;
      }
      disposeMaterial(glbMaterial);
    });
    this.solids = new BakedGeometry(objectParts.solids);
    this.others = new BakedGeometry(objectParts.others);
    this.room = new BakedGeometry(roomParts);
    const drawn = (geometry: THREE.BufferGeometry, material: THREE.Material, name: string) => {
      const mesh = new THREE.Mesh(geometry, material);
      mesh.name = name;
      mesh.matrixAutoUpdate = false;
      mesh.raycast = () => {}; // picking goes through the GLB's nodes
      this.view.add(mesh);
      return mesh;
    };
    drawn(this.solids.geometry, this.materials.solids, "objects").visible =
      objectParts.solids.length > 0;
    drawn(this.others.geometry, this.materials.others, "objects-two-sided").visible =
      objectParts.others.length > 0;
    this.roomMesh = drawn(this.room.geometry, this.materials.room, "glb-room");
    this.roomMesh.visible = roomParts.length > 0;
  }

  /** Parse GLB bytes; meshes named by object id take the object's colour in `colours`. */
  static async parse(
    bytes: ArrayBuffer,
    objects: readonly SceneObject[],
    colours: ReadonlyMap<string, Rgb> = new Map(),
  ): Promise<SceneModel> {
    const gltf = await new GLTFLoader().parseAsync(bytes, "");
    return new SceneModel(gltf.scene, objects, colours);
  }

  /** Colour the objects anew (the masks' colouring changed); glowing ones keep glowing. */
  recolour(colours: ReadonlyMap<string, Rgb>): void {
    for (const [id, parts] of this.partsOf) {
      const rgb = colours.get(id);
      if (!rgb) continue;
      for (const entry of parts) {
        entry.colour = new THREE.Color(rgbHex(rgb));
        this[entry.baked].setColour(
          entry.part,
          entry.colour,
          this.lit.has(id) ? HIGHLIGHT : undefined,
        );
      }
    }
  }

  /** The object id a mesh belongs to: the nearest node named by an object id (or a room surface). */
  private static idOf(node: THREE.Object3D, classOf: ReadonlyMap<string, string>): string | null {
    for (let at: THREE.Object3D | null = node; at; at = at.parent) {
      if (classOf.has(at.name) || isRoomSurface(at.name)) return at.name;
    }
    return null;
  }

  /** Draw the objects see-through (so points on their surfaces show), or solid again. */
  setSeeThrough(on: boolean): void {
    for (const material of [this.materials.solids, this.materials.others]) {
      material.transparent = on;
      material.opacity = on ? SEE_THROUGH_OPACITY : 1;
      material.depthWrite = !on;
      material.needsUpdate = true;
    }
  }

  /** Show or hide the GLB's own room (the view draws the layout's room itself when known). */
  setRoomVisible(visible: boolean): void {
    for (const node of this.roomNodes) node.visible = visible;
    this.roomMesh.visible = visible && this.roomNodes.length > 0;
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
    for (const id of new Set([...this.lit, ...ids])) {
      for (const { baked, part, colour } of this.partsOf.get(id) ?? []) {
        this[baked].setColour(part, colour, ids.has(id) ? HIGHLIGHT : undefined);
      }
    }
    this.lit = new Set(ids);
  }

  /** The colour an object is drawn in now (its first part's, linear), null for an unknown id. */
  colourOf(id: string): THREE.Color | null {
    const first = this.partsOf.get(id)?.[0];
    return first ? this[first.baked].colourOf(first.part) : null;
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
      if (node instanceof THREE.Mesh) node.geometry.dispose();
    });
    for (const baked of [this.solids, this.others, this.room]) baked.dispose();
    for (const material of Object.values(this.materials)) material.dispose();
  }
}

/** GLB nodes of the room itself (see backend export/glb.py): floor, ceiling, wall_0..wall_3. */
export function isRoomSurface(name: string): boolean {
  return name === "floor" || name === "ceiling" || /^wall_\d+$/.test(name);
}

function glbColour(material: THREE.Material): THREE.Color | undefined {
  const { color } = material as { color?: unknown };
  return color instanceof THREE.Color ? color.clone() : undefined;
}

function disposeMaterial(material: THREE.Material | THREE.Material[]): void {
  for (const m of Array.isArray(material) ? material : [material]) m.dispose();
}
