// The scene's objects in 3D: scene.glb of the current revision, coloured as their masks on the
// photo, brighter while hovered or selected. A new GLB is fetched only when the stages that made
// the revision change (edits keep them).
import type { SceneDocument } from "@holiscene/schema";
import type * as THREE from "three";
import { api } from "../../api/client";
import type { SceneSession } from "../../state/sceneSession";
import { maskColours } from "../objectColors";
import { maskStyle } from "../photo/maskStyle";
import { SceneModel } from "./sceneModel";
import type { Scene3dStatus } from "./viewportDom";

/** What the GLB depends on: the stages that made the revision (edits keep them). */
const glbKey = (doc: SceneDocument) => JSON.stringify(doc.scene.stages ?? []);

const meshStageRan = (doc: SceneDocument) =>
  (doc.scene.stages ?? []).some((stage) => stage.name === "scene_mesh");

/**
 * Whether a stage that writes scene.glb made the revision (the pipeline's scene_mesh, also run
 * by "Re-place objects") and had something to put in it (a placed object, the room, or a floor
 * at a known camera height and pitch; export/glb.py writes nothing otherwise, as for a photo of
 * one flat colour): without one there is none to ask for, and the 404 would show in the
 * console as an error.
 */
export const mayHaveGlb = (doc: SceneDocument): boolean => {
  const { objects, layout, camera } = doc.scene;
  if (!meshStageRan(doc)) return false;
  const floorKnown = camera?.height_m != null && camera.pitch_deg != null;
  return floorKnown || layout?.corners_3d != null || objects.some((o) => o.box_3d != null);
};

/** What the 3D view says when a revision has no 3D scene: why, and what brings one. */
export function missingSceneText(doc: SceneDocument): string {
  if (!meshStageRan(doc)) return "No 3D objects yet: they appear once the pipeline has run.";
  if (doc.scene.objects.length === 0) {
    return "No objects to show in 3D: add them on the photo (Box, Detect objects), then run the pipeline again.";
  }
  return "The pipeline placed no object in 3D: its warnings above say why.";
}

export interface ViewportObjectsInputs {
  scene: THREE.Scene;
  session: SceneSession;
  canvas: HTMLCanvasElement;
  setStatus(state: Scene3dStatus, text: string): void;
  requestRender(): void;
  /** The revision has no GLB (yet). */
  onMissing(): void;
  /** A GLB is in the scene; `first`: the first one the view shows. */
  onShown(first: boolean): void;
}

export class ViewportObjects {
  model: SceneModel | null = null;
  /** How long the last GLB took to parse and bake (milliseconds), for the benchmark. */
  lastLoadMs: number | null = null;
  /** glbKey of the revision whose GLB was asked for last. */
  private loadedGlb = "";
  private readonly abort = new AbortController();
  private readonly stopColours: () => void;
  /** Whether the objects are drawn see-through (kept for the next GLB). */
  private seeThrough = false;

  constructor(private readonly inputs: ViewportObjectsInputs) {
    this.stopColours = maskStyle.subscribe(() => {
      this.model?.recolour(this.colours());
      inputs.requestRender();
    });
  }

  /** Objects in 3D have the colours of their masks on the photo. */
  colours() {
    return maskColours(
      this.inputs.session.objects,
      maskStyle.get().colouring,
      this.inputs.session.doc.scene.removed_by_person,
    );
  }

  /** Whether the session's revision needs another GLB than the one shown. */
  get stale(): boolean {
    return glbKey(this.inputs.session.doc) !== this.loadedGlb;
  }

  /** Fetch and show the session's revision's GLB; failures end in the status line. */
  load(): Promise<void> {
    return this.fetchAndShow().catch((error: unknown) => {
      if (this.abort.signal.aborted) return;
      this.inputs.setStatus("error", `The 3D scene could not be shown: ${String(error)}`);
    });
  }

  private async fetchAndShow(): Promise<void> {
    const { scene, session, canvas, setStatus } = this.inputs;
    const doc = session.doc;
    this.loadedGlb = glbKey(doc);
    if (!this.model) setStatus("loading", "Loading the 3D scene…");
    // scene.glb is binary (and 404 means "no objects yet"): a plain fetch, not request().
    const response = mayHaveGlb(doc)
      ? await fetch(api.glbUrl(session.sceneId, doc.revision), { signal: this.abort.signal })
      : null;
    if (response === null || response.status === 404) {
      setStatus("missing", missingSceneText(doc));
      this.inputs.onMissing();
      return;
    }
    if (!response.ok) throw new Error(`scene.glb: ${response.status} ${response.statusText}`);
    const bytes = await response.arrayBuffer();
    const start = performance.now();
    const loaded = await SceneModel.parse(bytes, session.objects, this.colours());
    this.lastLoadMs = performance.now() - start;
    if (this.abort.signal.aborted) {
      loaded.dispose();
      return;
    }
    const first = this.model === null;
    if (this.model) {
      scene.remove(this.model.view);
      this.model.dispose();
    }
    this.model = loaded;
    loaded.setSeeThrough(this.seeThrough);
    scene.add(loaded.view);
    canvas.dataset.revision = String(doc.revision);
    this.highlight();
    this.inputs.onShown(first);
  }

  /** Draw the objects see-through, or solid again. */
  setSeeThrough(on: boolean): void {
    this.seeThrough = on;
    this.model?.setSeeThrough(on);
    this.inputs.requestRender();
  }

  /** Brighten the hovered and the selected object. */
  highlight(): void {
    const { session, canvas } = this.inputs;
    canvas.dataset.selected = session.selected ?? "";
    if (!this.model) return;
    this.model.highlight(new Set([session.hovered, session.selected].filter((id) => id !== null)));
    this.inputs.requestRender();
  }

  dispose(): void {
    this.abort.abort();
    this.stopColours();
    this.model?.dispose();
  }
}
