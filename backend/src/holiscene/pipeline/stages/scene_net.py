"""The learned camera, room and 3D boxes of thesis Ch. 5 (`learning.scene_net`: the layout
estimation and object detection networks), as alternatives to the geometry's stages:
`layout_by_network` in place of `layout_from_lines`, `boxes_by_network` in place of the
metrology and placement. Not in the default pipeline: on held-out rooms the geometry's
camera and room, and its boxes refined by `boxes_by_refiner`, measure better
(docs/benchmarks.md, "Geometry, learned, combined"); `infer --stages` picks them."""

from __future__ import annotations

import numpy as np

from ...geometry.camera import PinholeCamera
from ...learning.scene_net.runtime import scene_network
from ...learning.scene_net.targets import frame_of
from ..base import SceneContext, Stage, required
from ..registry import register_stage
from .layout import write_layout


@register_stage
class LayoutByNetwork(Stage):
    name = "layout_by_network"
    requires = frozenset({"image", "intrinsics", "objects"})
    provides = frozenset({"camera", "vanishing_points", "layout"})

    def run(self, ctx: SceneContext) -> None:
        K, source = required(ctx.intrinsics, "intrinsics")
        estimate = scene_network().estimate(ctx.image, K, required(ctx.objects, "objects"))
        room = estimate.room
        note = "camera and room from the layout network (learned; its scale is a guess)"
        frame = frame_of(room.pitch_deg, room.roll_deg, room.yaw_deg)
        write_layout(ctx, source, frame, room.corners_world(), room.camera_height_m, note)
        ctx.reports[self.name] = note


@register_stage
class BoxesByNetwork(Stage):
    name = "boxes_by_network"
    requires = frozenset({"image", "objects", "camera"})
    provides = frozenset({"boxes_3d"})
    single_photo_only = True

    def run(self, ctx: SceneContext) -> None:
        camera = required(ctx.camera, "camera")
        objects = required(ctx.objects, "objects")
        if camera.pitch_deg is None or camera.roll_deg is None:
            ctx.notes[self.name] = "no camera pitch and roll: no 3D boxes"
            ctx.boxes_3d = {o.id: None for o in objects}
            return
        K = np.asarray(camera.K, dtype=float)
        estimate = scene_network().estimate(ctx.image, K, objects)
        boxes = estimate.boxes(objects, PinholeCamera(K, camera.pitch_deg, camera.roll_deg))
        ctx.boxes_3d = {o.id: boxes.get(o.id) for o in objects}
        ctx.reports[self.name] = f"{len(boxes)} boxes from the object network (learned)"
