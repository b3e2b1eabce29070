// Many small meshes drawn as one, lit once: each part's triangles moved into world space and
// coloured per vertex with its diffuse (Lambert) shading under the view's fixed lights, so
// the 3D view draws 50 objects (or 50 arrows) in one draw call with the cheapest shader
// (MeshBasicMaterial with vertex colours). Diffuse light does not depend on the viewpoint,
// so orbiting does not change it. A part's colour can change afterwards (selection, hover)
// without rebuilding. Measured on SwiftShader (software WebGL) at the view's moving size: a
// visible triangle of a few pixels costs about a microsecond, a draw call some 25, and
// three.js's flat-shaded Lambert material works out each pixel's normal and light; baking
// removes the draw calls and the lighting, and culling closed solids (solidWinding) halves
// the triangles drawn.
import * as THREE from "three";

/** The view's lights (world frame): a sky/ground hemisphere and a sun, as three.js lights
 * them (linear colours times intensity). */
const SKY = new THREE.Color(0xffffff).multiplyScalar(2.2);
const GROUND = new THREE.Color(0x8a8577).multiplyScalar(2.2);
const SUN = new THREE.Color(0xffffff).multiplyScalar(1.6);
const TO_SUN = new THREE.Vector3(-2, 6, 3).normalize();
const UP = new THREE.Vector3(0, 1, 0);
const NO_GLOW = new THREE.Color(0x000000);

/** Diffuse reflectance factor at a world-space unit normal: three.js's MeshLambertMaterial
 * under the lights above (irradiance over pi), per colour channel. */
export function lambertShade(normal: THREE.Vector3, out = new THREE.Color()): THREE.Color {
  out.copy(GROUND).lerp(SKY, 0.5 * normal.dot(UP) + 0.5);
  const sun = Math.max(normal.dot(TO_SUN), 0);
  out.setRGB(out.r + SUN.r * sun, out.g + SUN.g * sun, out.b + SUN.b * sun);
  return out.multiplyScalar(1 / Math.PI);
}

export interface BakedPart {
  geometry: THREE.BufferGeometry;
  /** Where the part goes in the baked geometry's frame (e.g. the mesh's matrixWorld). */
  matrix: THREE.Matrix4;
  /** Diffuse colour (linear, as THREE.Color holds it). */
  colour: THREE.Color;
  /** Wind its triangles the other way (an inside-out solid, see solidWinding). */
  flip?: boolean;
}

export class BakedGeometry {
  readonly geometry = new THREE.BufferGeometry();
  /** Each part's first vertex and vertex count, in the order given. */
  private readonly ranges: { start: number; count: number }[] = [];
  /** Each vertex's shading factor (lambertShade of its normal), RGB. */
  private readonly shades: Float32Array;
  private readonly colours: THREE.BufferAttribute;

  constructor(given: readonly BakedPart[]) {
    const parts = given.map((part) => {
      const geometry = part.flip ? flipped(part.geometry) : part.geometry;
      // Without normals (the pipeline's GLB has none) faces are flat, as three.js draws them.
      return {
        ...part,
        geometry: geometry.hasAttribute("normal") ? geometry : flatShaded(geometry),
      };
    });
    let vertices = 0;
    let indices = 0;
    for (const { geometry } of parts) {
      const count = geometry.getAttribute("position").count;
      this.ranges.push({ start: vertices, count });
      vertices += count;
      indices += geometry.index ? geometry.index.count : count;
    }
    const positions = new Float32Array(vertices * 3);
    this.shades = new Float32Array(vertices * 3);
    const index = vertices > 65535 ? new Uint32Array(indices) : new Uint16Array(indices);
    const point = new THREE.Vector3();
    const shade = new THREE.Color();
    const normalMatrix = new THREE.Matrix3();
    let at = 0;
    parts.forEach(({ geometry, matrix }, i) => {
      const { start, count } = this.ranges[i] as { start: number; count: number };
      const position = geometry.getAttribute("position");
      const normal = geometry.getAttribute("normal");
      normalMatrix.getNormalMatrix(matrix);
      for (let v = 0; v < count; v++) {
        const o = (start + v) * 3;
        point.fromBufferAttribute(position, v).applyMatrix4(matrix).toArray(positions, o);
        point.fromBufferAttribute(normal, v).applyMatrix3(normalMatrix).normalize();
        lambertShade(point, shade).toArray(this.shades, o);
      }
      const source = geometry.index;
      const n = source ? source.count : count;
      for (let k = 0; k < n; k++) index[at + k] = start + (source ? source.getX(k) : k);
      at += n;
    });
    this.colours = new THREE.BufferAttribute(new Float32Array(vertices * 3), 3);
    this.geometry.setAttribute("position", new THREE.BufferAttribute(positions, 3));
    this.geometry.setAttribute("color", this.colours);
    this.geometry.setIndex(new THREE.BufferAttribute(index, 1));
    this.geometry.computeBoundingSphere();
    parts.forEach(({ colour }, i) => {
      this.setColour(i, colour);
    });
  }

  /** Colour part `i`: `colour` lit, plus `glow` (emitted light, as a material's emissive). */
  setColour(i: number, colour: THREE.Color, glow: THREE.Color = NO_GLOW): void {
    const range = this.ranges[i];
    if (!range) return;
    const array = this.colours.array as Float32Array;
    const rgb = [colour.r, colour.g, colour.b];
    const add = [glow.r, glow.g, glow.b];
    for (let k = range.start * 3; k < (range.start + range.count) * 3; k++) {
      array[k] = (rgb[k % 3] as number) * (this.shades[k] as number) + (add[k % 3] as number);
    }
    this.colours.needsUpdate = true;
  }

  /** Part `i`'s colour as drawn at its first vertex (linear). */
  colourOf(i: number): THREE.Color {
    const range = this.ranges[i];
    return new THREE.Color().fromBufferAttribute(this.colours, range ? range.start : 0);
  }

  dispose(): void {
    this.geometry.dispose();
  }
}

/** A geometry without normals as three.js shades it: each triangle flat (its own normal). */
function flatShaded(geometry: THREE.BufferGeometry): THREE.BufferGeometry {
  const flat = geometry.index ? geometry.toNonIndexed() : geometry.clone();
  flat.computeVertexNormals(); // unindexed: each vertex takes its triangle's normal
  return flat;
}

/** The same triangles wound the other way. */
function flipped(geometry: THREE.BufferGeometry): THREE.BufferGeometry {
  const copy = geometry.clone();
  const count = geometry.index ? geometry.index.count : geometry.getAttribute("position").count;
  const order = Array.from({ length: count }, (_, k) => geometry.index?.getX(k) ?? k);
  for (let k = 0; k + 2 < count; k += 3) {
    [order[k + 1], order[k + 2]] = [order[k + 2] as number, order[k + 1] as number];
  }
  copy.setIndex(order);
  return copy;
}

/**
 * Whether a mesh is closed (one solid or several) with all its triangles wound alike, and
 * which way, as placed by `matrix`: 1 counter-clockwise seen from outside (three.js's front
 * faces), -1 inside out, 0 neither (open, or wound both ways: it must be drawn two-sided).
 * Closed solids can be drawn one-sided: their back faces never show, and culling them halves
 * what a software rasterizer draws.
 */
export function solidWinding(geometry: THREE.BufferGeometry, matrix: THREE.Matrix4): 1 | -1 | 0 {
  const position = geometry.getAttribute("position");
  const index = geometry.index;
  const count = index ? index.count : position.count;
  if (count < 12 || count % 3 !== 0) return 0;
  const ids = vertexIdsByPosition(position);
  // Directed edge (p, q) -> how many triangles wind it, keyed p * vertices + q: numbers, not
  // strings, since a crowded room's GLB has some 10^5 triangles to go through on opening.
  const vertices = position.count;
  const edges = new Map<number, number>();
  const wind = (p: number, q: number) => {
    const key = p * vertices + q;
    edges.set(key, (edges.get(key) ?? 0) + 1);
  };
  const a = new THREE.Vector3();
  const b = new THREE.Vector3();
  const c = new THREE.Vector3();
  let volume = 0;
  for (let k = 0; k < count; k += 3) {
    const i = index ? index.getX(k) : k;
    const j = index ? index.getX(k + 1) : k + 1;
    const l = index ? index.getX(k + 2) : k + 2;
    const [p, q, r] = [ids[i] as number, ids[j] as number, ids[l] as number];
    if (p === q || q === r || r === p) continue; // degenerate: no area, no edges
    wind(p, q);
    wind(q, r);
    wind(r, p);
    a.fromBufferAttribute(position, i);
    b.fromBufferAttribute(position, j);
    c.fromBufferAttribute(position, l);
    volume += a.dot(b.cross(c)); // six times the signed volume of (origin, a, b, c)
  }
  // Closed and consistently wound: each edge is crossed as often one way as the other (parts
  // that touch, a table's top and legs, may share edges).
  for (const [key, times] of edges) {
    const p = Math.floor(key / vertices);
    const q = key - p * vertices;
    if (edges.get(q * vertices + p) !== times) return 0;
  }
  const signed = volume * Math.sign(matrix.determinant());
  return signed > 0 ? 1 : signed < 0 ? -1 : 0;
}

/** Each vertex's id by its position (to a micrometre): a solid stored with split vertices (a
 * seam, or a vertex per face for flat normals) is still closed. Vertices are sorted by their
 * rounded coordinates and equal neighbours share an id (no string keys). */
function vertexIdsByPosition(position: THREE.BufferAttribute | THREE.InterleavedBufferAttribute) {
  const n = position.count;
  const rounded = new Float64Array(n * 3);
  for (let v = 0; v < n; v++) {
    rounded[3 * v] = Math.round(position.getX(v) * 1e6);
    rounded[3 * v + 1] = Math.round(position.getY(v) * 1e6);
    rounded[3 * v + 2] = Math.round(position.getZ(v) * 1e6);
  }
  const order = Array.from({ length: n }, (_, v) => v);
  const compare = (u: number, v: number) =>
    (rounded[3 * u] as number) - (rounded[3 * v] as number) ||
    (rounded[3 * u + 1] as number) - (rounded[3 * v + 1] as number) ||
    (rounded[3 * u + 2] as number) - (rounded[3 * v + 2] as number);
  order.sort(compare);
  const ids = new Uint32Array(n);
  let id = 0;
  order.forEach((v, k) => {
    if (k > 0 && compare(order[k - 1] as number, v) !== 0) id += 1;
    ids[v] = id;
  });
  return ids;
}
