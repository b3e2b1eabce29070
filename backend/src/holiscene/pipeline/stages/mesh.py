"""The 3D scene file (GLB) of the placed objects and the floor."""

from __future__ import annotations

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
        ctx.scene_glb = scene_glb(placed, floor_y)
        if ctx.scene_glb is None:
            ctx.notes[self.name] = "nothing to show in 3D: no object placed and no floor found"
        else:
            ctx.notes[self.name] = "objects are boxes: the shape library is not used yet"
