"""Oriented 3D boxes: corners in the order of the contract's BOX_CORNER_SIGNS."""

from __future__ import annotations

import math

import numpy as np
from holiscene_schema import BOX_CORNER_SIGNS, Box3D

from .camera import FloatArray, rot_y

_SIGNS = np.array(BOX_CORNER_SIGNS, dtype=float)


def box_corners(center: FloatArray, size: FloatArray, yaw_deg: float) -> FloatArray:
    """The 8 world corners (8, 3) of a box with local size (front, up, right) and yaw about +y."""
    local = _SIGNS * (np.asarray(size, dtype=float) / 2.0)
    corners: FloatArray = local @ rot_y(math.radians(yaw_deg)).T + np.asarray(center, dtype=float)
    return corners


def corners_of(box: Box3D) -> FloatArray:
    """The 8 world corners of a contract box."""
    return box_corners(np.array(box.center), np.array(box.size), box.yaw_deg)
