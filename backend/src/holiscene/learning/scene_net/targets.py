"""What the layout and object networks predict, and how it turns back into a scene (numpy,
shared by training and run time). Thesis Ch. 5 (Total3DUnderstanding) parametrises the
camera and room for the LEN and each 3D box for the ODN; here:

- camera: pitch and roll (degrees);
- room: its yaw against the camera's heading in (-45, 45] (a room box looks the same turned by
  a quarter), the camera's height in metres, and the five other faces' distances from the
  camera in camera heights (`RoomHypothesis`: front, back, left, right along the room's axes,
  the ceiling above the camera);
- object, given the photo's camera and its 2D box: the offset of its projected 3D centre from
  the 2D box's centre (in box widths and heights), the log of the centre's distance from the
  camera, the log of its size over the class's typical size, and its yaw against the ray to
  its centre (what the pixels show: the same chair seen to the left or right of the photo
  turns with the ray).
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np
from holiscene_schema import Box3D

from ...geometry.camera import FloatArray, PinholeCamera
from ...geometry.manhattan import ManhattanFrame
from ...geometry.room_layout import RoomHypothesis, room_to_world
from ..box_refiner.features import typical_size

ROOM_DISTANCES = ("front", "back", "left", "right", "ceiling")  # in camera heights


def wrap_degrees(angle: float | FloatArray, period: float = 360.0) -> FloatArray:
    """An angle folded into [-period / 2, period / 2)."""
    result: FloatArray = (np.asarray(angle, dtype=float) + period / 2) % period - period / 2
    return result


def frame_of(pitch_deg: float, roll_deg: float, yaw_deg: float) -> ManhattanFrame:
    """A Manhattan frame known without lines (no segment families)."""
    return ManhattanFrame(pitch_deg, roll_deg, yaw_deg, np.zeros(0, dtype=np.int64), np.zeros(3))


@dataclass(frozen=True)
class RoomTargets:
    pitch_deg: float
    roll_deg: float
    yaw_deg: float
    camera_height_m: float
    distances: FloatArray  # ROOM_DISTANCES, camera heights

    @classmethod
    def of_truth(cls, pitch_deg: float, roll_deg: float, corners_world: FloatArray) -> RoomTargets:
        """The targets of a true room (8 world corners, metres, floor first)."""
        corners = np.asarray(corners_world, dtype=float)
        edge = corners[1] - corners[0]
        heading = math.degrees(math.atan2(-edge[2], edge[0]))
        yaw = float(wrap_degrees(heading, 90.0))
        to_room = room_to_world(frame_of(pitch_deg, roll_deg, yaw))
        metres = float(-corners[:, 1].min())
        room = RoomHypothesis.enclosing(corners @ to_room / metres)
        distances = np.array([getattr(room, name) for name in ROOM_DISTANCES])
        return cls(pitch_deg, roll_deg, yaw, metres, distances)

    def room(self) -> RoomHypothesis:
        values = dict(zip(ROOM_DISTANCES, self.distances.tolist(), strict=True))
        return RoomHypothesis(**values, score=0.0, ceiling_seen=False)

    def corners_world(self) -> FloatArray:
        """The room's 8 corners in the world frame, metres, contract order."""
        to_room = room_to_world(frame_of(self.pitch_deg, self.roll_deg, self.yaw_deg))
        result: FloatArray = self.room().corners_room() @ to_room.T * self.camera_height_m
        return result


def azimuth_deg(point: FloatArray) -> float:
    """The heading of a world point seen from the camera, as a box yaw: the yaw that turns a
    box's front (+x) towards it."""
    return math.degrees(math.atan2(-float(point[2]), float(point[0])))


@dataclass(frozen=True)
class ObjectTargets:
    centre_offset: FloatArray  # (2,) projected centre from the 2D box's centre, box sizes
    log_distance: float  # metres from the camera to the box's centre
    log_size: FloatArray  # (3,) log(size / typical size), the box's own (front, up, right)
    yaw_deg: float  # against the ray to the centre, [-180, 180)

    @classmethod
    def of_truth(
        cls,
        box: Box3D,
        bbox: Sequence[float],
        cls_name: str,
        camera: PinholeCamera,
    ) -> ObjectTargets | None:
        """None when the box's centre is behind the camera (no projected centre)."""
        centre = np.asarray(box.center, dtype=float)
        pixel = camera.project(centre)[0]
        if not np.isfinite(pixel).all():
            return None
        x1, y1, x2, y2 = bbox
        width, height = max(x2 - x1, 1.0), max(y2 - y1, 1.0)
        offset = np.array([(pixel[0] - (x1 + x2) / 2) / width, (pixel[1] - (y1 + y2) / 2) / height])
        log_size = np.log(
            np.maximum(np.asarray(box.size, dtype=float), 1e-3) / typical_size(cls_name)
        )
        yaw = float(wrap_degrees(box.yaw_deg - azimuth_deg(centre)))
        return cls(offset, math.log(max(float(np.linalg.norm(centre)), 1e-3)), log_size, yaw)

    def box(self, bbox: Sequence[float], cls_name: str, camera: PinholeCamera) -> Box3D:
        x1, y1, x2, y2 = bbox
        width, height = max(x2 - x1, 1.0), max(y2 - y1, 1.0)
        pixel = np.array(
            [
                (x1 + x2) / 2 + self.centre_offset[0] * width,
                (y1 + y2) / 2 + self.centre_offset[1] * height,
            ]
        )
        centre = camera.ray(pixel)[0] * math.exp(self.log_distance)
        size = typical_size(cls_name) * np.exp(self.log_size)
        yaw = float(wrap_degrees(self.yaw_deg + azimuth_deg(centre)))
        return Box3D(
            center=[round(float(v), 4) for v in centre],
            size=[round(float(v), 4) for v in size],
            yaw_deg=round(yaw, 3),
        )
