"""A stored scene back on the context, so later stages can run on it without the earlier ones.

A placement job (after a person moved the room layout) starts here: the objects, their masks,
the camera, the layout and the supports come from the scene revision it was asked on, the
photo from the scene's folder. The vanishing points are not stored; they follow from the
camera and the room's axes (the layout's yaw), as the layout stage would have found them.

A full re-run of a scene whose room layout a person set keeps that layout and the camera
fitted with it (`layout_from_revision` in place of `layout_from_lines`), as it keeps people's
supports; the other stages run again around them.
"""

from __future__ import annotations

from typing import Any

import numpy as np
from holiscene_schema import Camera, Scene

from ...geometry.camera import FloatArray, PinholeCamera
from ...geometry.manhattan import room_directions
from ...placement.room import Room
from ...segmentation.rle import decode_mask
from ..base import (
    ObjectMask,
    PipelineBuildError,
    SceneContext,
    Stage,
    StageFailedError,
    required,
)
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
        self.scene = _stored_scene(self.name, scene)

    def run(self, ctx: SceneContext) -> None:
        scene = _same_photo(ctx, self.scene)
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
        ctx.vanishing_points = vanishing_points(camera, corners)


def has_hand_set_layout(scene: Scene) -> bool:
    """Whether a person set the scene's room layout (a `set_layout` edit), with the camera
    pitch and roll fitted to it: then a full re-run keeps both."""
    camera = scene.camera
    return (
        scene.layout.source == "manual"
        and scene.layout.corners_3d is not None
        and camera is not None
        and camera.pitch_deg is not None
        and camera.roll_deg is not None
    )


@register_stage
class LayoutFromRevision(Stage):
    """The room layout a person set, and the camera fitted with it (K, pitch, roll, height),
    as stored: `layout_from_lines`'s outputs without looking at the photo's lines."""

    name = "layout_from_revision"
    requires = frozenset({"image", "intrinsics"})
    provides = frozenset({"camera", "vanishing_points", "layout"})

    def __init__(self, scene: Scene | None = None, **rest: Any) -> None:
        super().__init__(**rest)
        self.scene = _stored_scene(self.name, scene)

    def run(self, ctx: SceneContext) -> None:
        scene = _same_photo(ctx, self.scene)
        camera, corners = scene.camera, scene.layout.corners_3d
        if not has_hand_set_layout(scene) or camera is None or corners is None:
            raise StageFailedError("the stored scene has no room layout set by hand to keep")
        K, _ = required(ctx.intrinsics, "intrinsics")
        ctx.camera = camera
        ctx.layout = scene.layout
        ctx.vanishing_points = vanishing_points(camera, corners)
        note = (
            "kept the room layout set by hand, and the camera's pitch, roll and height fitted to it"
        )
        if np.allclose(K, np.asarray(camera.K, dtype=float)):
            ctx.reports[self.name] = note
        else:
            ctx.notes[self.name] = (
                f"{note} (with the intrinsics it was fitted under, not this run's)"
            )


def vanishing_points(camera: Camera, corners: list[list[float]]) -> FloatArray:
    """The three vanishing points (rows: vertical first) of a room seen by a camera: the
    room's axes (its yaw) in the image, as the layout stage finds them from lines."""
    if camera.pitch_deg is None or camera.roll_deg is None:
        raise StageFailedError("the camera has no pitch/roll: no vanishing points")
    K = np.asarray(camera.K, dtype=float)
    yaw = Room.from_corners(np.asarray(corners, dtype=float)).yaw_deg
    pinhole = PinholeCamera(K, camera.pitch_deg, camera.roll_deg)
    points = (K @ pinhole.world_from_cv.T @ room_directions(yaw).T).T
    result: FloatArray = points / np.linalg.norm(points, axis=1, keepdims=True)
    return result


def _stored_scene(stage: str, scene: Scene | None) -> Scene:
    if scene is None:
        raise PipelineBuildError(f"stage {stage!r} needs the stored scene (option scene)")
    return scene


def _same_photo(ctx: SceneContext, scene: Scene) -> Scene:
    if (ctx.width, ctx.height) != (scene.image.width, scene.image.height):
        raise StageFailedError("the stored scene was made from a photo of another size")
    return scene
