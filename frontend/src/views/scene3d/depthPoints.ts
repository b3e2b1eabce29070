// Each object's points from the depth, for scenes that came with depth: what the depth camera
// saw of it (partial: the mask's pixels back-projected) and what shape completion made of them
// (completed: the network's points before meshing), both from GET .../depth-points. Shown by
// the toolbar's "Depth points" checkbox with a key over the view; the objects (the points lie
// on their surfaces) and the photo on its frustum (they lie behind it seen from the photo's
// viewpoint) are drawn see-through meanwhile.
import type { DepthPoints } from "@holiscene/schema";
import * as THREE from "three";
import { api } from "../../api/client";
import { el } from "../../dom";
import type { SceneSession } from "../../state/sceneSession";
import "./depthPoints.css";

/** The viser viewer's colours (viewer/scene_viewer.py PARTIAL_RGB, COMPLETED_RGB). */
export const DEPTH_POINT_COLOURS = { partial: "#f97316", completed: "#0d9488" } as const;
export type DepthPointKind = keyof typeof DEPTH_POINT_COLOURS;
const KINDS: DepthPointKind[] = ["partial", "completed"];
/** On the screen, whatever the distance: a far object's points stay visible. */
const POINT_SIZE_PX = 3;

/** The two clouds (every object's points of a kind in one draw call) of one revision. */
export class DepthPointClouds {
  readonly root = new THREE.Group();
  /** The revision whose points are loaded (or being loaded). */
  private revision: number | null = null;
  private loading: Promise<void> | null = null;
  private readonly clouds = new Map<DepthPointKind, THREE.Points>();

  constructor(private readonly sceneId: string) {
    this.root.name = "depth-points";
    this.root.visible = false;
  }

  /** Load the revision's points unless they are loaded; rejects with the server's reason. */
  load(revision: number, signal: AbortSignal): Promise<void> {
    if (this.revision === revision && this.loading) return this.loading;
    this.revision = revision;
    this.loading = api.depthPoints(this.sceneId, revision, signal).then((data) => {
      if (this.revision === revision) this.build(data);
    });
    this.loading.catch(() => {
      if (this.revision === revision) this.revision = null; // asked again next time
    });
    return this.loading;
  }

  private build(data: DepthPoints): void {
    this.clear();
    for (const kind of KINDS) {
      const flat = data.objects.flatMap((o) => (o[kind] ?? []).flat());
      const geometry = new THREE.BufferGeometry();
      geometry.setAttribute("position", new THREE.Float32BufferAttribute(flat, 3));
      const material = new THREE.PointsMaterial({
        color: new THREE.Color(DEPTH_POINT_COLOURS[kind]),
        size: POINT_SIZE_PX,
        sizeAttenuation: false,
      });
      const cloud = new THREE.Points(geometry, material);
      cloud.name = `depth-points-${kind}`;
      cloud.raycast = () => {}; // clicks pick the objects, never the points
      this.clouds.set(kind, cloud);
      this.root.add(cloud);
    }
  }

  /** The points drawn of a kind, flat x, y, z in the world frame (for the end-to-end probe). */
  positions(kind: DepthPointKind): number[] {
    const attribute = this.clouds.get(kind)?.geometry.getAttribute("position");
    return attribute ? Array.from(attribute.array as Float32Array) : [];
  }

  private clear(): void {
    for (const cloud of this.clouds.values()) {
      this.root.remove(cloud);
      cloud.geometry.dispose();
      (cloud.material as THREE.Material).dispose();
    }
    this.clouds.clear();
  }

  dispose(): void {
    this.clear();
  }
}

/** The toolbar's checkbox and the key shown over the view while it is ticked. */
export function depthPointControls(onChange: (on: boolean) => void): {
  toggle: HTMLLabelElement;
  key: HTMLElement;
  /** Say something in the key instead of the legend (null: the legend). */
  setMessage(text: string | null): void;
} {
  const input = el("input", {
    testid: "toggle-depth-points",
    attrs: { type: "checkbox" },
    on: { change: () => onChange(input.checked) },
  });
  const toggle = el(
    "label",
    {
      className: "toggle",
      attrs: {
        title: "The depth's points of each object: as seen, and as shape completion completed them",
      },
    },
    input,
    "Depth points",
  );
  const item = (kind: DepthPointKind, text: string) =>
    el(
      "span",
      { className: "legend-item" },
      el("span", {
        className: "swatch swatch--point",
        attrs: { style: `background: ${DEPTH_POINT_COLOURS[kind]}` },
      }),
      text,
    );
  const legend = el(
    "span",
    { className: "scene3d-key-items" },
    item("partial", "seen by the depth camera"),
    item("completed", "completed shape"),
  );
  const message = el("span", { className: "scene3d-key-message", testid: "depth-points-message" });
  const key = el(
    "div",
    {
      className: "scene3d-key",
      testid: "depth-points-key",
      attrs: { "aria-label": "Depth point colours" },
    },
    legend,
    message,
  );
  key.hidden = true;
  message.hidden = true;
  return {
    toggle,
    key,
    setMessage(text) {
      message.textContent = text ?? "";
      message.hidden = text === null;
      legend.hidden = text !== null;
    },
  };
}

export interface DepthPointsInputs {
  scene: THREE.Scene;
  session: SceneSession;
  /** Where the checkbox goes. */
  toolbar: HTMLElement;
  /** Where the key goes (over the canvas). */
  viewport: HTMLElement;
  /** Draw what could hide the points (the objects, the photo) see-through, or not. */
  seeThrough(on: boolean): void;
  requestRender(): void;
}

/** The depth points of the session's scene, with their checkbox and key; for scenes with depth. */
export function mountDepthPoints(inputs: DepthPointsInputs): {
  clouds: DepthPointClouds;
  /** The session has another revision: load its points if they are shown. */
  refresh(): void;
  dispose(): void;
} {
  const { scene, session, requestRender } = inputs;
  const clouds = new DepthPointClouds(session.sceneId);
  const abort = new AbortController();
  let shown = false;
  const show = () => {
    if (!shown) return;
    const revision = session.doc.revision;
    controls.setMessage("Loading the depth points…");
    clouds.load(revision, abort.signal).then(
      () => {
        if (session.doc.revision !== revision || !shown) return;
        controls.setMessage(null);
        requestRender();
      },
      (error: unknown) => {
        if (abort.signal.aborted) return;
        controls.setMessage(`No depth points: ${error instanceof Error ? error.message : error}`);
      },
    );
  };
  const controls = depthPointControls((on) => {
    shown = on;
    clouds.root.visible = on;
    controls.key.hidden = !on;
    inputs.seeThrough(on);
    requestRender();
    show();
  });
  scene.add(clouds.root);
  inputs.toolbar.append(controls.toggle);
  inputs.viewport.append(controls.key);
  return {
    clouds,
    refresh: show,
    dispose() {
      abort.abort();
      scene.remove(clouds.root);
      clouds.dispose();
    },
  };
}
