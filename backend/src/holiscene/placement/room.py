"""The room cuboid of a layout as a frame: floor, ceiling, wall rectangles, and the camera.

Frames as in docs/architecture.md, "Conventions": world origin at the camera centre, x
forward, y up, z right. A box's own axes are (front, up, right); yaw turns them about +y, so
a box's front in the world is (cos yaw, 0, -sin yaw).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from holiscene_schema import Camera, Layout

from ..geometry.camera import FloatArray, PinholeCamera, rot_y

UP = np.array([0.0, 1.0, 0.0])


def front_of(yaw_deg: float) -> FloatArray:
    """The world direction a box of this yaw faces (its own +x)."""
    yaw = math.radians(yaw_deg)
    return np.array([math.cos(yaw), 0.0, -math.sin(yaw)])


def yaw_of(direction: FloatArray) -> float:
    """The yaw (degrees) whose front is the horizontal part of `direction`."""
    return math.degrees(math.atan2(-float(direction[2]), float(direction[0])))


def wrap_deg(angle: float, period: float = 360.0) -> float:
    """`angle` wrapped into [-period/2, period/2)."""
    return (angle + period / 2.0) % period - period / 2.0


@dataclass(frozen=True)
class Rect:
    """A vertical rectangle things can hang on: a wall, or a side face of a box.

    `normal` is horizontal and points to where an attached object sits (into the room for a
    wall, out of the box for a face); `tangent` = up x normal runs along it.
    """

    name: str
    centre: FloatArray  # on the plane, at mid height
    normal: FloatArray
    half_length: float
    y_min: float
    y_max: float

    @property
    def tangent(self) -> FloatArray:
        result: FloatArray = np.cross(UP, self.normal)
        return result

    def point(self, along: float, altitude: float) -> FloatArray:
        """The point `along` metres from the centre (along the tangent) at height y."""
        result: FloatArray = self.centre + self.tangent * along
        result[1] = altitude
        return result

    def hit(self, ray: FloatArray) -> float | None:
        """Distance along a ray from the camera (origin) to this plane, if in front."""
        denom = float(ray @ self.normal)
        if abs(denom) < 1e-9:
            return None
        t = float(self.centre @ self.normal) / denom
        return t if t > 1e-6 else None


@dataclass(frozen=True)
class Room:
    """The layout's cuboid: centre, yaw of its axes, size (depth x, height, width z)."""

    centre: FloatArray
    yaw_deg: float
    size: FloatArray

    @classmethod
    def from_corners(cls, corners: FloatArray) -> Room:
        c = np.asarray(corners, dtype=float)
        x_axis = c[1] - c[0]
        z_axis = c[3] - c[0]
        size = np.array(
            [
                float(np.linalg.norm(x_axis)),
                float(c[4:, 1].mean() - c[:4, 1].mean()),
                float(np.linalg.norm(z_axis)),
            ]
        )
        return cls(centre=c.mean(axis=0), yaw_deg=yaw_of(x_axis), size=size)

    @property
    def floor_y(self) -> float:
        return float(self.centre[1] - self.size[1] / 2.0)

    @property
    def ceiling_y(self) -> float:
        return float(self.centre[1] + self.size[1] / 2.0)

    @property
    def rotation(self) -> FloatArray:
        return rot_y(math.radians(self.yaw_deg))

    def to_local(self, points: FloatArray) -> FloatArray:
        result: FloatArray = (np.atleast_2d(points) - self.centre) @ self.rotation
        return result

    def holds(self, point: FloatArray) -> bool:
        """Whether `point` lies strictly inside the room."""
        local = self.to_local(point)[0]
        return bool((np.abs(local) < self.size / 2.0).all())

    def walls(self) -> list[Rect]:
        """The four walls, normals pointing into the room."""
        d, w = self.size[0] / 2.0, self.size[2] / 2.0
        rot = self.rotation
        out = []
        for name, local_normal, half_length in (
            ("wall_x+", np.array([-1.0, 0.0, 0.0]), w),
            ("wall_x-", np.array([1.0, 0.0, 0.0]), w),
            ("wall_z+", np.array([0.0, 0.0, -1.0]), d),
            ("wall_z-", np.array([0.0, 0.0, 1.0]), d),
        ):
            offset = -local_normal * (d if local_normal[0] else w)
            out.append(
                Rect(
                    name=name,
                    centre=self.centre + rot @ offset,
                    normal=rot @ local_normal,
                    half_length=float(half_length),
                    y_min=self.floor_y,
                    y_max=self.ceiling_y,
                )
            )
        return out

    def walls_by_ray(self, ray: FloatArray) -> list[Rect]:
        """Walls ordered by where a ray from the camera leaves the room through them."""
        hits = []
        for wall in self.walls():
            t = wall.hit(ray)
            if t is not None and float(ray @ wall.normal) < 0:  # leaving through it
                hits.append((t, wall))
        hits.sort(key=lambda item: item[0])
        return [wall for _, wall in hits]


def box_faces(center: FloatArray, size: FloatArray, yaw_deg: float) -> list[Rect]:
    """The four side faces of a box, normals pointing out of the box."""
    rot = rot_y(math.radians(yaw_deg))
    d, h, w = np.asarray(size, dtype=float) / 2.0
    out = []
    for name, local_normal, half_depth, half_length in (
        ("front", np.array([1.0, 0.0, 0.0]), d, w),
        ("back", np.array([-1.0, 0.0, 0.0]), d, w),
        ("right", np.array([0.0, 0.0, 1.0]), w, d),
        ("left", np.array([0.0, 0.0, -1.0]), w, d),
    ):
        out.append(
            Rect(
                name=name,
                centre=np.asarray(center, dtype=float) + rot @ (local_normal * half_depth),
                normal=rot @ local_normal,
                half_length=float(half_length),
                y_min=float(center[1] - h),
                y_max=float(center[1] + h),
            )
        )
    return out


def pinhole(camera: Camera) -> PinholeCamera | None:
    """The contract camera as a pinhole camera, or None without pitch and roll."""
    if camera.pitch_deg is None or camera.roll_deg is None:
        return None
    return PinholeCamera(np.array(camera.K, dtype=float), camera.pitch_deg, camera.roll_deg)


def projection_matrix(camera: PinholeCamera) -> FloatArray:
    """P (3x3) with homogeneous pixels = P @ world point (the camera sits at the origin)."""
    result: FloatArray = camera.K @ camera.world_from_cv.T
    return result


def room_of(layout: Layout | None) -> Room | None:
    if layout is None or layout.corners_3d is None:
        return None
    room = Room.from_corners(np.array(layout.corners_3d, dtype=float))
    if not np.all(room.size > 0.3):
        return None
    return room


def _walls_outward(floor: FloatArray) -> list[tuple[FloatArray, FloatArray]]:
    """Each wall of a floor's 4 corners (x, z), wall i from corner i to i + 1: a point on it
    and its unit normal pointing out of the room."""
    middle = floor.mean(axis=0)
    walls = []
    for i in range(4):
        a, b = floor[i], floor[(i + 1) % 4]
        edge = b - a
        outward = np.array([edge[1], -edge[0]]) / max(float(np.linalg.norm(edge)), 1e-9)
        if outward @ (middle - a) > 0:
            outward = -outward
        walls.append((a, outward))
    return walls


def _move_wall(corners: FloatArray, wall: int, shift: FloatArray) -> None:
    """Move wall `wall`'s two floor corners and the two above them by `shift` (x, z)."""
    for corner in (wall, (wall + 1) % 4):
        corners[corner, [0, 2]] += shift
        corners[corner + 4, [0, 2]] += shift


def widened_to_hold(corners: FloatArray, boxes: list[FloatArray]) -> tuple[FloatArray, list[float]]:
    """The room's corners (floor 0-3, the ceiling's 4-7 above them) with each wall moved out
    along its normal just far enough that every box (its 8 corners) is on the room's side of
    it, and how far each of the four walls moved (0 for a wall no box crosses)."""
    widened = np.array(corners, dtype=float)
    points = np.concatenate(boxes)[:, [0, 2]] if boxes else np.zeros((0, 2))
    moves = []
    for i, (a, outward) in enumerate(_walls_outward(widened[:4, [0, 2]])):
        beyond = float(((points - a) @ outward).max()) if len(points) else 0.0
        move = max(beyond, 0.0)
        moves.append(move)
        _move_wall(widened, i, outward * move)
    return widened, moves


def narrowed_to_hung(
    corners: FloatArray, hung: list[FloatArray], boxes: list[FloatArray], camera_gap: float
) -> tuple[FloatArray, list[float]]:
    """The room's corners with each wall that something hangs on (a hung box whose centre is
    nearer that wall than any other) moved in along its normal until the nearest box (hung or
    not: every box stays inside) touches it, the camera staying `camera_gap` metres inside;
    and how far each wall moved in (0 for one nothing hangs on, or already touched). The
    walls are read from boxes inside the room (`widened_to_hold` first)."""
    narrowed = np.array(corners, dtype=float)
    walls = _walls_outward(narrowed[:4, [0, 2]])
    points = np.concatenate(boxes)[:, [0, 2]] if boxes else np.zeros((0, 2))
    hung_walls = set()
    for box in hung:
        centre = box[:, [0, 2]].mean(axis=0)
        hung_walls.add(int(np.argmin([float((a - centre) @ out) for a, out in walls])))
    moves = []
    for i, (a, outward) in enumerate(walls):
        if i not in hung_walls or not len(points):
            moves.append(0.0)
            continue
        room_left = float(((a - points) @ outward).min())  # to the nearest box's point
        move = max(min(room_left, float(a @ outward) - camera_gap), 0.0)
        moves.append(move)
        _move_wall(narrowed, i, -outward * move)
    return narrowed, moves
