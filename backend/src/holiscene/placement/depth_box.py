"""An object's 3D box from the depth under its mask, in the room's axes.

The mask is eroded (its edges bleed onto whatever is behind) and depths far from the
object's own are dropped; the points' robust extents give the sides the camera sees, the
class's typical size the hidden back (extended away from the camera, never through a wall),
and the supporter the bottom: the floor, or the top of the box it stands on.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import cv2
import numpy as np
from holiscene_schema import Box3D

from ..geometry.camera import FloatArray, PinholeCamera
from ..geometry.depth_points import back_project
from ..knowledge.object_sizes import middle_size
from .room import Room, wrap_deg

MIN_POINTS = 20
MAX_POINTS = 5000  # more add nothing to percentiles but time
EDGE_PERCENTILE = 3.0  # robust extents: the points' 3rd to 97th percentiles
MAD_LIMIT = 4.0  # depths further than this many (scaled) MADs from the median are dropped
MIN_DEPTH_BAND_M = 0.15
MIN_SIZE_M = 0.03


@dataclass(frozen=True)
class Support:
    """What the object's bottom rests on: a height, or None to take it from the points."""

    bottom_y: float | None


def object_points(mask: np.ndarray, depth: np.ndarray, camera: PinholeCamera) -> FloatArray | None:
    """World points (N, 3) under the eroded mask, depth outliers dropped; None when too few."""
    area = int(mask.sum())
    iterations = int(np.clip(round(0.04 * math.sqrt(area)), 1, 4))
    eroded = cv2.erode(mask.astype(np.uint8), np.ones((3, 3), np.uint8), iterations=iterations)
    inside = eroded.astype(bool) if eroded.sum() >= MIN_POINTS else mask
    rows, cols = np.nonzero(inside & (depth > 0))
    if len(rows) < MIN_POINTS:
        return None
    if len(rows) > MAX_POINTS:
        pick = np.linspace(0, len(rows) - 1, MAX_POINTS).astype(int)
        rows, cols = rows[pick], cols[pick]
    z = depth[rows, cols]
    median = float(np.median(z))
    spread = 1.4826 * float(np.median(np.abs(z - median)))
    keep = np.abs(z - median) <= max(MAD_LIMIT * spread, MIN_DEPTH_BAND_M)
    if keep.sum() < MIN_POINTS:
        return None
    pixels = np.column_stack([cols[keep], rows[keep]]).astype(float)
    points: FloatArray = back_project(depth, camera.K, pixels) @ camera.world_from_cv.T
    return points


def _extend(
    lo: float, hi: float, size: float, wall_lo: float, wall_hi: float
) -> tuple[float, float]:
    """Grow [lo, hi] to `size` on the side away from the camera (at 0), within the walls."""
    if hi - lo >= size:
        return lo, hi
    if (lo + hi) / 2.0 >= 0.0:
        hi = min(lo + size, max(wall_hi, hi))
    else:
        lo = max(hi - size, min(wall_lo, lo))
    return lo, hi


def box_from_points(
    points: FloatArray, cls: str, room: Room, support: Support, turn_deg: float
) -> Box3D:
    """The box aligned with the room's axes holding the points, completed by the class's
    typical size where the points see only the front; `turn_deg` (a multiple of 90) turns
    the box's front from the room's x axis (the placement's choice of the object's front)."""
    local = points @ room.rotation
    low = np.percentile(local, EDGE_PERCENTILE, axis=0)
    high = np.percentile(local, 100.0 - EDGE_PERCENTILE, axis=0)
    depth_m, _, width_m = middle_size(cls)
    # The longer seen side takes the class's longer typical side.
    long_axis, short_axis = (0, 2) if high[0] - low[0] >= high[2] - low[2] else (2, 0)
    walls_lo = room.centre @ room.rotation - room.size / 2.0
    walls_hi = room.centre @ room.rotation + room.size / 2.0
    bounds = {}
    for axis, size in ((long_axis, max(depth_m, width_m)), (short_axis, min(depth_m, width_m))):
        bounds[axis] = _extend(low[axis], high[axis], size, walls_lo[axis], walls_hi[axis])
    bottom = support.bottom_y if support.bottom_y is not None else float(low[1])
    top = max(float(high[1]), bottom + MIN_SIZE_M)
    lo = np.array([bounds[0][0], bottom, bounds[2][0]])
    hi = np.array([bounds[0][1], top, bounds[2][1]])
    size = np.maximum(hi - lo, MIN_SIZE_M)
    centre = ((lo + hi) / 2.0) @ room.rotation.T
    if round(turn_deg / 90.0) % 2:
        size = size[[2, 1, 0]]
    return Box3D(
        center=[round(float(v), 4) for v in centre],
        size=[round(float(v), 4) for v in size],
        yaw_deg=round(wrap_deg(room.yaw_deg + turn_deg), 3),
    )


def quarter_turn(placed_yaw: float | None, room_yaw: float) -> float:
    """The multiple of 90 degrees closest to the placed box's turn from the room's axes."""
    if placed_yaw is None:
        return 0.0
    return 90.0 * round(wrap_deg(placed_yaw - room_yaw) / 90.0)
