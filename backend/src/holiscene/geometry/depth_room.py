"""The room from depth: the floor plane (so pitch, roll and the camera's height, an exact
metric scale), the room's yaw from the walls' normals, and the walls and ceiling the depth
sees as the farthest planes along the room's axes.

Planes are found among points whose normals agree with the expected direction; parallel
surfaces (a table top above the floor, a cabinet's front before the wall) are told apart by
their level: the floor is the lowest horizontal level, a wall the farthest vertical one.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from .camera import FloatArray, PinholeCamera
from .depth_points import (
    PointGrid,
    fit_plane_lsq,
    fit_plane_ransac,
    level_clusters,
    pitch_roll_from_up,
)
from .manhattan import room_directions

NORMAL_TOLERANCE_DEG = 20.0  # a point's normal this close to a plane's counts for it
FLOOR_TOLERANCE_DEG = 30.0  # the vanishing points' up may be off by this much
LEVEL_BIN_M = 0.05
FLOOR_BAND_M = 0.15  # the floor's points are within this of its lowest level
# A point is on a plane within 2 cm plus 1% of its depth (a depth sensor's noise grows with
# distance; synthetic depth is exact).
PLANE_INLIER_M = 0.02
PLANE_INLIER_PER_M = 0.01
# A level needs this share of the grid's points (at least MIN_LEVEL_POINTS) to be a surface.
MIN_LEVEL_SHARE = 0.004
MIN_LEVEL_POINTS = 25
# A wall or ceiling bounds what the depth sees: no more than a sliver of points (openings,
# noise) lies beyond it. A plane with points well beyond it is furniture before the wall.
BEYOND_M = 0.10
BEYOND_SHARE = 0.002
# A wall runs from the floor to the ceiling: the points of a plane taken for a side wall must
# span this much in height (the side of a cabinet before it does not). The front wall is
# exempt: the photo often shows only its strip between furniture and the frame's top.
MIN_WALL_SPAN_M = 1.2
YAW_SEARCH_DEG = 12.0  # normals this close to the commonest direction refine it


@dataclass(frozen=True)
class FloorFit:
    pitch_deg: float
    roll_deg: float
    camera_height: float  # metres: the camera's distance to the floor plane
    inliers: int  # grid points on the floor


def _min_points(grid: PointGrid) -> int:
    return max(MIN_LEVEL_POINTS, int(MIN_LEVEL_SHARE * len(grid.points)))


def fit_floor(grid: PointGrid, up_guess_cv: FloatArray) -> FloorFit | None:
    """The floor: RANSAC among the points whose normals are within FLOOR_TOLERANCE_DEG of the
    expected up, near the lowest level they reach; None when the depth shows no floor."""
    up = up_guess_cv / np.linalg.norm(up_guess_cv)
    normals_ok = np.nan_to_num(grid.normals @ up) > math.cos(math.radians(FLOOR_TOLERANCE_DEG))
    candidates = grid.points[normals_ok]
    if len(candidates) < _min_points(grid):
        return None
    levels = level_clusters(candidates @ up, LEVEL_BIN_M, _min_points(grid))
    if not levels:
        return None
    near = np.abs(candidates @ up - levels[0]) < FLOOR_BAND_M
    if near.sum() < 3:
        return None
    threshold = PLANE_INLIER_M + PLANE_INLIER_PER_M * candidates[:, 2]
    plane, _ = fit_plane_ransac(candidates[near], up, threshold[near])
    # Refitted on every candidate near the plane: the band about the lowest level may have
    # cut a noisy floor's points unevenly.
    inliers = np.abs(plane.distances(candidates)) < threshold
    plane = fit_plane_lsq(candidates[inliers], up)
    pitch, roll = pitch_roll_from_up(plane.normal)
    return FloorFit(pitch, roll, plane.offset, int(inliers.sum()))


def refine_yaw(grid: PointGrid, camera: PinholeCamera, yaw_deg: float) -> float:
    """The room's yaw from the wall-like normals (horizontal ones): the direction modulo 90
    degrees most of them share, refined by the median of those within YAW_SEARCH_DEG of
    it; `yaw_deg` (the vanishing points') when too few normals are horizontal."""
    normals = grid.normals @ camera.world_from_cv.T
    horizontal = np.nan_to_num(np.abs(normals[:, 1]), nan=1.0) < math.sin(
        math.radians(NORMAL_TOLERANCE_DEG)
    )
    flat = normals[horizontal]
    if len(flat) < _min_points(grid):
        return yaw_deg
    angles = np.degrees(np.arctan2(-flat[:, 2], flat[:, 0]))
    # The most common direction modulo 90 degrees: a histogram of 1-degree bins, smoothed
    # over 5 (walls and furniture sides share the room's axes).
    counts = np.bincount(np.floor(angles % 90.0).astype(int) % 90, minlength=90)
    smoothed = sum(np.roll(counts, shift) for shift in range(-2, 3))
    mode = float(np.argmax(smoothed)) + 0.5
    offset = (angles - mode + 45.0) % 90.0 - 45.0
    close = np.abs(offset) < YAW_SEARCH_DEG / 2
    if close.sum() < _min_points(grid):
        return yaw_deg
    yaw = mode + float(np.median(offset[close]))
    # The room's yaw is defined up to quarter turns: the one nearest the vanishing points'.
    return yaw_deg + ((yaw - yaw_deg + 45.0) % 90.0 - 45.0)


# Each face: the room axis its distance is measured along, the sign of that axis towards it.
FACES: dict[str, tuple[int, float]] = {
    "front": (0, 1.0),
    "left": (2, -1.0),
    "right": (2, 1.0),
    "ceiling": (1, 1.0),
}


def _room_points(grid: PointGrid, camera: PinholeCamera, yaw_deg: float) -> FloatArray:
    dirs = room_directions(yaw_deg)
    to_room = np.column_stack([dirs[1], dirs[0], dirs[2]])  # room x, y, z in world
    result: FloatArray = grid.points @ camera.world_from_cv.T @ to_room
    return result


def points_reach(grid: PointGrid, camera: PinholeCamera, yaw_deg: float) -> dict[str, float]:
    """How far (metres) the points reach towards each face: a face the depth does not see
    is at least this far (furniture before it, or a sliver of it seen)."""
    points = _room_points(grid, camera, yaw_deg)
    return {
        face: float(np.percentile(points[:, axis] * sign, 99.9))
        for face, (axis, sign) in FACES.items()
    }


def seen_faces(grid: PointGrid, camera: PinholeCamera, yaw_deg: float) -> dict[str, float]:
    """Distance (metres, from the camera) of each wall and of the ceiling the depth sees: the
    farthest level of the points whose normals face back along that face's axis, when
    hardly any point lies beyond it."""
    dirs = room_directions(yaw_deg)
    to_room = np.column_stack([dirs[1], dirs[0], dirs[2]])  # room x, y, z in world
    points = _room_points(grid, camera, yaw_deg)
    normals = np.nan_to_num(grid.normals @ camera.world_from_cv.T @ to_room)
    cos_tol = math.cos(math.radians(NORMAL_TOLERANCE_DEG))
    found: dict[str, float] = {}
    for face, (axis, sign) in FACES.items():
        facing = normals[:, axis] * sign < -cos_tol  # the face's normal points at the camera
        distances = points[facing, axis] * sign
        levels = level_clusters(distances[distances > 0], LEVEL_BIN_M, _min_points(grid))
        if not levels:
            continue
        band = np.abs(distances - levels[-1]) < LEVEL_BIN_M
        level = float(np.median(distances[band]))
        beyond = points[:, axis] * sign > level + BEYOND_M
        heights = points[facing][band, 1]
        tall = face in ("front", "ceiling") or float(np.ptp(heights)) >= MIN_WALL_SPAN_M
        if tall and beyond.sum() <= BEYOND_SHARE * len(points):
            found[face] = level
    return found
