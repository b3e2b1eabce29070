"""A scene context filled from a synthetic scene's ground truth (an oracle for the stages
before metrology): objects and 2D boxes, masks (exact, or the filled 2D boxes), supports,
camera, layout, and the vanishing points of the true camera and room axes.

Used by the tests and the benchmark of metrology, placement and model fitting, so these
stages are measured on their own, not through the errors of the stages before them.
"""

from __future__ import annotations

from typing import Literal

import numpy as np
from holiscene_schema import Scene

from ..geometry.camera import FloatArray, PinholeCamera
from ..pipeline.base import ObjectMask, SceneContext
from ..segmentation.rle import decode_mask
from ..synth.generate import SyntheticScene
from .room import Room, projection_matrix

MaskKind = Literal["truth", "box"]


def vanishing_points(camera: PinholeCamera, room_yaw_deg: float) -> FloatArray:
    """Rows: the vertical vanishing point, then those of the room's x and z axes (unit
    homogeneous vectors)."""
    P = projection_matrix(camera)
    yaw = np.radians(room_yaw_deg)
    directions = np.array(
        [[0.0, 1.0, 0.0], [np.cos(yaw), 0.0, -np.sin(yaw)], [np.sin(yaw), 0.0, np.cos(yaw)]]
    )
    vps = directions @ P.T
    result: FloatArray = vps / np.linalg.norm(vps, axis=1, keepdims=True)
    return result


def context_from_truth(
    synthetic: SyntheticScene, masks: MaskKind = "truth", with_supports: bool = True
) -> SceneContext:
    truth: Scene = synthetic.truth
    assert truth.camera is not None and truth.layout.corners_3d is not None
    width, height = truth.image.width, truth.image.height
    ctx = SceneContext(image=synthetic.frame.rgb)
    ctx.objects = [
        o.model_copy(update={"mask": None, "box_3d": None, "corners_3d": None, "mesh": None})
        for o in truth.objects
    ]
    ctx.masks = {}
    for obj in truth.objects:
        if masks == "truth" and obj.mask is not None:
            pixels = decode_mask(obj.mask, width, height)
            ctx.masks[obj.id] = ObjectMask(pixels=pixels, source="ground_truth")
        else:
            pixels = np.zeros((height, width), dtype=bool)
            x1, y1, x2, y2 = (round(v) for v in obj.bbox)
            pixels[y1:y2, x1:x2] = True
            ctx.masks[obj.id] = ObjectMask(pixels=pixels, source="box")
    ctx.camera = truth.camera
    ctx.intrinsics = (np.array(truth.camera.K), "given")
    ctx.layout = truth.layout
    if with_supports:
        ctx.supports = list(truth.supports)
    camera = PinholeCamera(
        np.array(truth.camera.K), truth.camera.pitch_deg or 0.0, truth.camera.roll_deg or 0.0
    )
    room = Room.from_corners(np.array(truth.layout.corners_3d))
    ctx.vanishing_points = vanishing_points(camera, room.yaw_deg)
    return ctx
