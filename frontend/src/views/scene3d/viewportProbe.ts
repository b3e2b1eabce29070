// The end-to-end tests' window into the 3D view (Scene3dProbe): read from the view's parts.

import * as THREE from "three";
import type { DepthPointClouds } from "./depthPoints";
import type { ViewportCamera } from "./viewportCamera";
import type { Scene3dProbe } from "./viewportDom";
import type { LiveLayers } from "./viewportLive";
import type { ViewportObjects } from "./viewportObjects";
import type { ViewportPicking } from "./viewportPicking";
import type { FrameStats, ViewportRender } from "./viewportRender";

export interface ProbeInputs {
  stats: FrameStats;
  renderer: THREE.WebGLRenderer;
  frames: ViewportRender;
  view: ViewportCamera;
  live: LiveLayers;
  objects: ViewportObjects;
  picking: ViewportPicking;
  depthPoints: DepthPointClouds | null;
}

export function scene3dProbe(inputs: ProbeInputs): Scene3dProbe {
  const { stats, renderer, frames, view, live, objects, picking, depthPoints } = inputs;
  return {
    get frames() {
      return stats.frames;
    },
    get renderMs() {
      return stats.renderMs;
    },
    roomCorners: () => (live.room.room ? live.room.corners() : null),
    cameraPose: () => (live.frustum ? live.frustum.pitchRoll : null),
    frustumShown: () => live.frustumShown,
    photoOnFrustum: () => live.frustum?.hasPhoto ?? false,
    arrows: () => live.arrows.arrows.map(({ child, parent, type }) => ({ child, parent, type })),
    screenPointOf: (id) => picking.screenPointOf(id),
    objectColour: (id) => objects.model?.colourOf(id)?.toArray() ?? null,
    orbit: (azimuth) => view.orbit(azimuth),
    depthPoints: () =>
      depthPoints && {
        shown: depthPoints.root.visible,
        partial: depthPoints.positions("partial"),
        completed: depthPoints.positions("completed"),
      },
    glbLoad: () => {
      const { model, lastLoadMs } = objects;
      if (!model || lastLoadMs === null) return null;
      let triangles = 0;
      model.root.traverse((node) => {
        if (!(node instanceof THREE.Mesh)) return;
        const geometry = node.geometry as THREE.BufferGeometry;
        triangles += (geometry.index?.count ?? geometry.getAttribute("position").count) / 3;
      });
      return { ms: lastLoadMs, triangles };
    },
    renderInfo: () => ({
      calls: renderer.info.render.calls,
      triangles: renderer.info.render.triangles,
      ...frames.lastFrameSize,
    }),
  };
}
