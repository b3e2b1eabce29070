"""SUN RGB-D's coordinate frames and their conversion into HoliScene's world frame.

Frames (all with the origin at the camera centre, metres):
- OpenCV camera frame: x right, y down, z forward (what K maps to pixels).
- SUN gravity frame: the frame of `annotation3Dfinal` and `annotation3Dlayout` (their X, Y
  and Z): x right, y down along gravity, z forward, both horizontal axes level. The rotation
  in `extrinsics/*.txt` (its first three columns, E) takes OpenCV camera coordinates to it:
  p_sun = E p_cv. (SUN's toolbox works in (X, Z, -Y), x right, y forward, z up, and its
  Rtilt is E written in that frame; the two agree point for point.)
- World frame (docs/architecture.md): x forward along the camera's heading, y up, z right.
  The SUN gravity frame's horizontal axes need not follow the camera's heading, so the
  conversion also turns about the vertical until the optical axis has no sideways part.

A box of `annotation3Dfinal` is a floor polygon (X, Z of its 4 corners, in order) and its
vertical extent Ymin..Ymax (y down, so Ymin is its top). Its front, as in SUN's toolbox, is
the side between the first two corners: the box faces from its centre towards that side.
"""

from __future__ import annotations

import math

import numpy as np

from ...geometry.boxes import box_corners
from ...geometry.camera import FloatArray, pitch_roll_from_up_direction, rot_y
from ..validation import InputError

# (right, down, forward) -> (forward, up, right): the same turn for the OpenCV camera frame
# and the SUN gravity frame, both being right-handed with y down.
FUR_FROM_RDF = np.array([[0.0, 0.0, 1.0], [0.0, -1.0, 0.0], [1.0, 0.0, 0.0]])
ROTATION_TOLERANCE = 1e-2  # extrinsics are written with a few decimals


def rotation_from_extrinsics(numbers: list[float]) -> FloatArray:
    """E (SUN gravity frame from OpenCV camera frame) from the numbers of an extrinsics file:
    3 rows of 4 (the rotation's row and a translation, which SUN leaves at zero and which is
    not used: annotations and camera share the origin), or the 3x3 rotation alone, which is
    all SUN's toolbox reads of the file. Made exactly orthonormal."""
    if len(numbers) not in (9, 12):
        raise InputError(
            f"must hold 3 rows of 4 numbers (or the 3x3 rotation), it holds {len(numbers)} numbers"
        )
    rotation = np.array(numbers, dtype=float).reshape(3, -1)[:, :3]
    if not np.all(np.isfinite(rotation)):
        raise InputError("holds a value that is not finite")
    if (
        np.abs(rotation @ rotation.T - np.eye(3)).max() > ROTATION_TOLERANCE
        or np.linalg.det(rotation) < 0
    ):
        raise InputError("its first three columns are not a rotation")
    u, _, vt = np.linalg.svd(rotation)
    result: FloatArray = u @ vt
    return result


def camera_heading_deg(sun_from_cv: FloatArray) -> float:
    """The camera's heading in the SUN gravity frame, as a yaw about the up axis in the
    world frame's convention (a direction (cos a, 0, -sin a) in forward/up/right axes has
    heading a): 0 when the optical axis points along the gravity frame's z."""
    axis = FUR_FROM_RDF @ sun_from_cv[:, 2]
    return math.degrees(math.atan2(-axis[2], axis[0]))


def world_from_sun(sun_from_cv: FloatArray) -> FloatArray:
    """Rotation taking SUN gravity-frame coordinates to world coordinates: the axes renamed
    (right, down, forward -> forward, up, right), then turned about +y by minus the
    camera's heading, so the camera looks along world +x with no yaw."""
    turn = rot_y(-math.radians(camera_heading_deg(sun_from_cv)))
    result: FloatArray = turn @ FUR_FROM_RDF
    return result


def camera_pitch_roll(sun_from_cv: FloatArray) -> tuple[float, float]:
    """Pitch and roll in degrees (docs/architecture.md): world up, seen in OpenCV camera
    coordinates, is the gravity frame's up (0, -1, 0) taken back through E."""
    up_cv = sun_from_cv.T @ np.array([0.0, -1.0, 0.0])
    return pitch_roll_from_up_direction(up_cv)


def floor_points_world(xs: list[float], zs: list[float], to_world: FloatArray) -> FloatArray:
    """The (N, 3) world points of a floor polygon given by its SUN gravity-frame X and Z
    (its height set to 0: only the horizontal part is used)."""
    sun = np.stack([np.asarray(xs, float), np.zeros(len(xs)), np.asarray(zs, float)], axis=1)
    result: FloatArray = sun @ to_world.T
    return result


def yaw_of(direction: FloatArray) -> float:
    """The yaw in degrees of a horizontal world direction (front (cos a, 0, -sin a) has yaw a)."""
    return math.degrees(math.atan2(-direction[2], direction[0]))


def horizontal_box(
    points: FloatArray, yaw_deg: float, y_bottom: float, y_top: float
) -> tuple[FloatArray, FloatArray]:
    """Centre and size (front, up, right) of the box with the given yaw holding the world
    points of a floor polygon, from world height y_bottom to y_top."""
    yaw = math.radians(yaw_deg)
    front = np.array([math.cos(yaw), 0.0, -math.sin(yaw)])
    right = np.array([math.sin(yaw), 0.0, math.cos(yaw)])
    along, across = points @ front, points @ right
    centre = (
        front * (along.max() + along.min()) / 2
        + right * (across.max() + across.min()) / 2
        + np.array([0.0, (y_bottom + y_top) / 2, 0.0])
    )
    size = np.array([np.ptp(along), y_top - y_bottom, np.ptp(across)])
    return centre, size


def object_box(
    xs: list[float], zs: list[float], y_min: float, y_max: float, to_world: FloatArray
) -> tuple[FloatArray, FloatArray, float]:
    """Centre, size and yaw (degrees) in the world frame of an annotation3Dfinal box: its 4
    floor corners (SUN gravity-frame X, Z) and Ymin, Ymax (y down). Its front is the side
    between the first two corners, as SUN's toolbox reads it."""
    if len(xs) != 4 or len(zs) != 4:
        raise InputError(f"a box's floor polygon has 4 corners, it has {len(xs)}")
    points = floor_points_world(xs, zs, to_world)
    middle = points.mean(axis=0)
    front = (points[0] + points[1]) / 2 - middle
    if np.linalg.norm(front) < 1e-9:
        raise InputError("a box's floor polygon has no area")
    yaw = yaw_of(front)
    low, high = sorted((-float(y_min), -float(y_max)))  # world y is up, SUN's Y down
    centre, size = horizontal_box(points, yaw, low, high)
    return centre, size, yaw


def room_corners(
    xs: list[float], zs: list[float], y_min: float, y_max: float, to_world: FloatArray
) -> FloatArray:
    """The 8 world corners (order of BOX_CORNER_SIGNS) of the room cuboid of
    annotation3Dlayout: its 4 floor corners and Ymin, Ymax. A room has no front of its own:
    its front is the wall direction closest to the camera's heading (yaw in [-45, 45))."""
    if len(xs) != 4 or len(zs) != 4:
        raise InputError(f"the room's floor polygon has {len(xs)} corners, not a cuboid's 4")
    points = floor_points_world(xs, zs, to_world)
    yaw = (yaw_of(points[1] - points[0]) + 45.0) % 90.0 - 45.0
    low, high = sorted((-float(y_min), -float(y_max)))
    centre, size = horizontal_box(points, yaw, low, high)
    return box_corners(centre, size, yaw)
