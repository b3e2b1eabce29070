"""Each object's points from the depth, as the `shape_completion` stage sees them: the partial
points (its mask's pixels with depth, back-projected into the world, depth outliers dropped)
and the network's completed points (before meshing), in the world frame of the scene's 3D
boxes; subsampled, for the workbench's 3D view and the viser viewer to draw.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from holiscene_schema import Scene

from ...core.errors import DomainError
from ...geometry.camera import FloatArray
from ...inputs.depth import METRES_PER_UNIT, depth_from_png
from ...placement.depth_box import object_points
from ...placement.room import pinhole
from ...segmentation.rle import decode_mask
from .runtime import completer

# Per list (partial, completed): enough to see a shape, and a room of a dozen objects stays
# under a megabyte of JSON.
MAX_POINTS = 1000


class DepthPointsError(DomainError):
    """The scene's depth cannot be placed in its world yet (HTTP 409)."""

    status = 409


@dataclass(frozen=True)
class ObjectPoints:
    id: str
    partial: FloatArray  # (N, 3) world frame, metres
    completed: FloatArray | None  # (M, 3); None without a box or with too few points in it


def subsample(points: FloatArray, limit: int) -> FloatArray:
    """At most `limit` of the points, evenly spread over their order (the same every time)."""
    if len(points) <= limit:
        return points
    pick = np.linspace(0, len(points) - 1, limit).round().astype(int)
    result: FloatArray = points[pick]
    return result


def stored_depth(scene: Scene, png: bytes) -> np.ndarray:
    """The scene's stored depth file (a 16-bit PNG in its DepthRef's units) in metres."""
    unit = scene.depth.metres_per_unit if scene.depth is not None else METRES_PER_UNIT
    width, height = scene.image.width, scene.image.height
    return depth_from_png(png, width, height, metres_per_unit=unit).metres


def scene_depth_points(
    scene: Scene, depth: np.ndarray, limit: int = MAX_POINTS
) -> list[ObjectPoints]:
    """The points of every object with a mask, in the scene's order."""
    if scene.camera is None or (camera := pinhole(scene.camera)) is None:
        raise DepthPointsError(
            "the scene has no camera pitch and roll yet to place the depth: run the pipeline"
        )
    width, height = scene.image.width, scene.image.height
    model = None
    out = []
    for obj in scene.objects:
        if obj.mask is None:
            continue
        points = object_points(decode_mask(obj.mask, width, height), depth, camera)
        if points is None:
            out.append(ObjectPoints(obj.id, np.zeros((0, 3)), None))
            continue
        completed = None
        if obj.box_3d is not None:
            model = model or completer()
            completed = model.complete_points(points, obj.box_3d)
        out.append(
            ObjectPoints(
                obj.id,
                subsample(points, limit),
                None if completed is None else subsample(completed, limit),
            )
        )
    return out
