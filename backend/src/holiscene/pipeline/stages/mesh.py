"""The 3D scene file (GLB): the placed objects (fitted models, or boxes) and the room.

Reads the optional slots `object_meshes` (from `shapes_fit`) and `layout` when an earlier
stage filled them: objects with a fitted model are drawn as it, the others as their boxes;
the room is the layout's cuboid (floor, ceiling and walls facing inwards), or else a floor
plane at the camera's height.
"""

from __future__ import annotations

import numpy as np
import trimesh
from holiscene_schema import Box3D

from ...export.glb import scene_glb
from ..base import SceneContext, Stage, required
from ..registry import register_stage


@register_stage
class SceneMesh(Stage):
    name = "scene_mesh"
    requires = frozenset({"objects", "boxes_3d", "camera"})
    provides = frozenset({"scene_glb"})

    def run(self, ctx: SceneContext) -> None:
        boxes = required(ctx.boxes_3d, "boxes_3d")
        camera = required(ctx.camera, "camera")
        placed: dict[str, tuple[str, Box3D]] = {}
        for obj in required(ctx.objects, "objects"):
            box = boxes.get(obj.id)
            if box is not None:
                placed[obj.id] = (obj.cls, box)
        known_floor = camera.height_m is not None and camera.pitch_deg is not None
        floor_y = -camera.height_m if known_floor and camera.height_m is not None else None
        meshes: dict[str, trimesh.Trimesh] = {
            obj_id: fitted.mesh
            for obj_id, fitted in (ctx.object_meshes or {}).items()
            if obj_id in placed
        }
        corners = ctx.layout.corners_3d if ctx.layout is not None else None
        room = np.array(corners, dtype=float) if corners is not None else None
        ctx.scene_glb = scene_glb(placed, floor_y, meshes, room)
        if ctx.scene_glb is None:
            ctx.notes[self.name] = "nothing to show in 3D: no object placed and no floor found"
        elif len(meshes) < len(placed):
            boxed = len(placed) - len(meshes)
            ctx.notes[self.name] = f"{boxed} of {len(placed)} objects drawn as boxes (no model)"
