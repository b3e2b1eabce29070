"""What the viewer draws, as plain numbers: object boxes, the room, support arrows.

No viser here, so the geometry is testable on its own. World frame as everywhere: origin at
the camera, y up, x forward, z right, metres.

Support arrows run from the supporter to the supported object (thesis figures: red = from
below, blue = from behind). They start at the supporter (an object's box centre; for the
floor the floor point under the object, for a wall the nearest wall point at the object's
height, for the ceiling the point above it) and pass through the object, so the head sticks
out on its far side: above a thing standing on something, in front of a thing hanging on a
wall. An arrow that only went centre to centre would be hidden inside the meshes.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from holiscene_schema import STRUCTURAL_SUPPORTERS, Scene, SceneObject, SupportType

from ..geometry.boxes import corners_of
from ..geometry.camera import FloatArray

# The 12 edges of a box, by corner index in the contract order (bottom face, top face).
BOX_EDGES: tuple[tuple[int, int], ...] = (
    (0, 1), (1, 2), (2, 3), (3, 0),
    (4, 5), (5, 6), (6, 7), (7, 4),
    (0, 4), (1, 5), (2, 6), (3, 7),
)  # fmt: skip

# How far the head sticks out of the supported object, metres: far enough to be seen against
# the room rather than against the object (a blue arrow on a blue door would vanish).
ARROW_OVERSHOOT = 0.2
MIN_ARROW_LENGTH = 0.4  # thin things (pictures) still get a visible arrow
WALL_FALLBACK_DISTANCE = 0.4  # no room layout: the wall is taken this far behind the object


def object_corners(obj: SceneObject) -> FloatArray | None:
    """The object's 8 box corners (contract order), from `corners_3d` or else `box_3d`."""
    if obj.corners_3d is not None:
        return np.asarray(obj.corners_3d, dtype=float)
    if obj.box_3d is not None:
        return corners_of(obj.box_3d)
    return None


def box_edge_segments(corners: FloatArray) -> FloatArray:
    """(12, 2, 3) line segments of a box's edges, for viser's line segments."""
    return np.stack([[corners[i], corners[j]] for i, j in BOX_EDGES])


def room_corners(scene: Scene) -> FloatArray | None:
    corners = scene.layout.corners_3d
    return np.asarray(corners, dtype=float) if corners is not None else None


def floor_height(scene: Scene) -> float | None:
    """y of the floor: the room's bottom face, else minus the camera's height."""
    room = room_corners(scene)
    if room is not None:
        return float(room[:4, 1].mean())
    if scene.camera is not None and scene.camera.height_m is not None:
        return -scene.camera.height_m
    return None


def ceiling_height(scene: Scene) -> float | None:
    room = room_corners(scene)
    return float(room[4:, 1].mean()) if room is not None else None


def nearest_wall_point(room: FloatArray, point: FloatArray) -> FloatArray:
    """The point of the room's four walls (vertical, through the floor's edges) nearest to
    `point`, at the point's height."""
    best: FloatArray | None = None
    best_distance = np.inf
    p = np.array([point[0], point[2]])
    for i in range(4):
        a = room[i, [0, 2]]
        b = room[(i + 1) % 4, [0, 2]]
        edge = b - a
        t = float(np.clip((p - a) @ edge / max(float(edge @ edge), 1e-12), 0.0, 1.0))
        q = a + t * edge
        distance = float(np.linalg.norm(p - q))
        if distance < best_distance:
            best_distance = distance
            best = np.array([q[0], point[1], q[1]])
    assert best is not None
    return best


@dataclass(frozen=True)
class SupportArrow:
    child: str
    parent: str
    type: SupportType
    start: FloatArray  # (3,) on the supporter
    end: FloatArray  # (3,) just beyond the supported object


@dataclass(frozen=True)
class ArrowPlan:
    arrows: list[SupportArrow]
    skipped: dict[str, str]  # child id -> why it has no arrow


def _extent_along(corners: FloatArray, direction: FloatArray) -> float:
    """How far the box reaches from its centre along a unit direction."""
    return float(((corners - corners.mean(axis=0)) @ direction).max())


def _structural_anchor(scene: Scene, parent: str, centre: FloatArray) -> FloatArray | None:
    if parent == "floor":
        y = floor_height(scene)
        return None if y is None else np.array([centre[0], y, centre[2]])
    if parent == "ceiling":
        y = ceiling_height(scene)
        return None if y is None else np.array([centre[0], y, centre[2]])
    room = room_corners(scene)
    if room is not None:
        return nearest_wall_point(room, centre)
    # No room: the wall is behind the object as seen from the camera (at the origin).
    away = np.array([centre[0], 0.0, centre[2]])
    norm = float(np.linalg.norm(away))
    if norm < 1e-9:
        return None
    anchored: FloatArray = centre + away / norm * WALL_FALLBACK_DISTANCE
    return anchored


def support_arrows(scene: Scene) -> ArrowPlan:
    """One arrow per support whose object and supporter have a place in 3D."""
    corners = {o.id: c for o in scene.objects if (c := object_corners(o)) is not None}
    arrows: list[SupportArrow] = []
    skipped: dict[str, str] = {}
    for support in scene.supports:
        child = corners.get(support.child)
        if child is None:
            skipped[support.child] = "no 3D box"
            continue
        centre = child.mean(axis=0)
        if support.parent in STRUCTURAL_SUPPORTERS:
            start = _structural_anchor(scene, support.parent, centre)
            if start is None:
                skipped[support.child] = f"the {support.parent} is not placed (no room layout)"
                continue
        elif support.parent in corners:
            start = corners[support.parent].mean(axis=0)
        else:
            skipped[support.child] = f"its supporter {support.parent} has no 3D box"
            continue
        offset = centre - start
        length = float(np.linalg.norm(offset))
        # Supporter and object sharing a centre: point up.
        direction = offset / length if length > 1e-6 else np.array([0.0, 1.0, 0.0])
        end = centre + direction * (_extent_along(child, direction) + ARROW_OVERSHOOT)
        if float(np.linalg.norm(end - start)) < MIN_ARROW_LENGTH:
            start = end - direction * MIN_ARROW_LENGTH
        arrows.append(
            SupportArrow(support.child, support.parent, support.type, np.asarray(start), end)
        )
    return ArrowPlan(arrows, skipped)


def scene_centre(scene: Scene) -> FloatArray:
    """Where to look: the room's centre, else the objects', else 3 m ahead of the camera."""
    room = room_corners(scene)
    if room is not None:
        centre: FloatArray = room.mean(axis=0)
        return centre
    points = [c for o in scene.objects if (c := object_corners(o)) is not None]
    if points:
        mean: FloatArray = np.vstack(points).mean(axis=0)
        return mean
    return np.array([3.0, 0.0, 0.0])
