"""A stored scene back on the context, so later stages can run on it without the earlier ones.

A placement job (after a person moved the room layout) starts here: the objects, their masks,
the camera, the layout and the supports come from the scene revision it was asked on, the
photo from the scene's folder. The vanishing points are not stored; they follow from the
camera and the room's axes (the layout's yaw), as the layout stage would have found them.
"""

from __future__ import annotations

from typing import Any

import numpy as np
from holiscene_schema import Scene

from ...geometry.camera import PinholeCamera
from ...geometry.manhattan import room_directions
from ...placement.room import Room
from ...rle import decode_mask
from ..base import ObjectMask, PipelineBuildError, SceneContext, Stage, StageFailedError
from ..registry import register_stage


@register_stage
class SceneFromRevision(Stage):
    name = "scene_from_revision"
    requires = frozenset({"image"})
    provides = frozenset(
        {"objects", "intrinsics", "masks", "camera", "vanishing_points", "layout", "supports"}
    )

    def __init__(self, scene: Scene | None = None, **rest: Any) -> None:
        super().__init__(**rest)
        if scene is None:
            raise PipelineBuildError(f"stage {self.name!r} needs the stored scene (option scene)")
        self.scene = scene

    def run(self, ctx: SceneContext) -> None:
        scene = self.scene
        if (ctx.width, ctx.height) != (scene.image.width, scene.image.height):
            raise StageFailedError("the stored scene was made from a photo of another size")
        camera = scene.camera
        if camera is None:
            raise StageFailedError("the scene has no camera: run the whole pipeline first")
        K = np.asarray(camera.K, dtype=float)
        ctx.intrinsics = (K, camera.K_source)
        ctx.camera = camera
        ctx.layout = scene.layout
        # Objects as stored minus what placement will compute again.
        ctx.objects = [
            o.model_copy(update={"box_3d": None, "corners_3d": None, "note": None})
            for o in scene.objects
        ]
        ctx.masks = {
            o.id: ObjectMask(decode_mask(o.mask, ctx.width, ctx.height), o.mask.source)
            for o in scene.objects
            if o.mask is not None
        }
        ctx.supports = list(scene.supports)
        ctx.vanishing_points = np.zeros((0, 3))  # none: later stages fall back to priors
        corners = scene.layout.corners_3d
        if camera.pitch_deg is None or camera.roll_deg is None or corners is None:
            ctx.notes[self.name] = "no camera pitch/roll or room layout stored: heights are priors"
            return
        yaw = Room.from_corners(np.asarray(corners, dtype=float)).yaw_deg
        pinhole = PinholeCamera(K, camera.pitch_deg, camera.roll_deg)
        points = (K @ pinhole.world_from_cv.T @ room_directions(yaw).T).T
        ctx.vanishing_points = points / np.linalg.norm(points, axis=1, keepdims=True)
