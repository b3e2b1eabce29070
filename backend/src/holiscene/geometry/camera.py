"""Pinhole camera with pitch and roll, in the Total3DUnderstanding-compatible world frame.

Frames:
- OpenCV camera frame: x right, y down, z forward (what K maps to pixels).
- World frame: origin at the camera centre, x horizontal forward, y up, z right.
A camera with pitch 0 and roll 0 looks along world +x. `world_from_camera` rotates first by
roll about the optical axis, then by pitch down about the right axis:
R = Rz(-pitch) @ Rx(roll), acting on (forward, up, right) camera coordinates.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from functools import cached_property

import numpy as np
from numpy.typing import NDArray

FloatArray = NDArray[np.float64]

# OpenCV (right, down, forward) -> (forward, up, right) and back.
_CV_TO_FUR = np.array([[0.0, 0.0, 1.0], [0.0, -1.0, 0.0], [1.0, 0.0, 0.0]])


def rot_x(angle: float) -> FloatArray:
    c, s = math.cos(angle), math.sin(angle)
    return np.array([[1.0, 0.0, 0.0], [0.0, c, -s], [0.0, s, c]])


def rot_y(angle: float) -> FloatArray:
    c, s = math.cos(angle), math.sin(angle)
    return np.array([[c, 0.0, s], [0.0, 1.0, 0.0], [-s, 0.0, c]])


def rot_z(angle: float) -> FloatArray:
    c, s = math.cos(angle), math.sin(angle)
    return np.array([[c, -s, 0.0], [s, c, 0.0], [0.0, 0.0, 1.0]])


@dataclass(frozen=True)
class PinholeCamera:
    K: FloatArray
    pitch_deg: float
    roll_deg: float

    # Cached: layout search projects thousands of short segments with one camera.
    @cached_property
    def world_from_cv(self) -> FloatArray:
        """Rotation taking OpenCV camera coordinates to world coordinates."""
        pitch, roll = math.radians(self.pitch_deg), math.radians(self.roll_deg)
        result: FloatArray = rot_z(-pitch) @ rot_x(roll) @ _CV_TO_FUR
        return result

    def ray(self, pixels: FloatArray) -> FloatArray:
        """Unit world directions of the rays through pixels (N, 2)."""
        pts = np.atleast_2d(np.asarray(pixels, dtype=float))
        to_world = self._world_from_pixel
        d_world = pts @ to_world[:, :2].T + to_world[:, 2]
        result: FloatArray = d_world / np.sqrt(np.einsum("ij,ij->i", d_world, d_world))[:, None]
        return result

    @cached_property
    def _world_from_pixel(self) -> FloatArray:
        result: FloatArray = self.world_from_cv @ np.linalg.inv(self.K)
        return result

    @cached_property
    def optical_axis(self) -> FloatArray:
        """Unit world direction the camera looks along."""
        result: FloatArray = self.world_from_cv[:, 2].copy()
        return result

    def project(self, points: FloatArray) -> FloatArray:
        """Pixels (N, 2) of world points (N, 3); points behind the camera give NaN."""
        pts = np.atleast_2d(np.asarray(points, dtype=float))
        p_cv = pts @ self.world_from_cv  # row-vector form of R^T p
        depth = p_cv[:, 2]
        with np.errstate(divide="ignore", invalid="ignore"):
            uvw = p_cv @ self.K.T
            uv = uvw[:, :2] / uvw[:, 2:3]
        uv[depth <= 1e-9] = np.nan
        result: FloatArray = uv
        return result


def pitch_roll_from_up_direction(up_cv: FloatArray) -> tuple[float, float]:
    """Pitch and roll (degrees) from the world's up direction seen in OpenCV camera coordinates.

    With R = Rz(-pitch) Rx(roll), world up in (forward, up, right) camera coordinates is
    (-sin p, cos p cos r, -cos p sin r); see the module docstring.
    """
    u = np.asarray(up_cv, dtype=float)
    u = u / np.linalg.norm(u)
    if u[1] > 0:  # the direction must point up in the image (negative OpenCV y)
        u = -u
    forward, up, right = u[2], -u[1], u[0]
    pitch = math.degrees(math.asin(max(-1.0, min(1.0, -forward))))
    roll = math.degrees(math.atan2(-right, up))
    return pitch, roll


def default_intrinsics(width: int, height: int, horizontal_fov_deg: float = 60.0) -> FloatArray:
    """Square-pixel intrinsics with the principal point at the image centre."""
    f = (width / 2.0) / math.tan(math.radians(horizontal_fov_deg) / 2.0)
    return np.array([[f, 0.0, width / 2.0], [0.0, f, height / 2.0], [0.0, 0.0, 1.0]])
