"""Where pixels meet horizontal planes, and heights along verticals: single-view metrology
in its simplest form, for a camera with known pitch, roll and height."""

from __future__ import annotations

import numpy as np

from .camera import FloatArray, PinholeCamera

MAX_DISTANCE_M = 30.0


def hit_horizontal_plane(
    camera: PinholeCamera, pixels: FloatArray, plane_y: float
) -> FloatArray | None:
    """World points where rays through pixels meet the horizontal plane y = plane_y."""
    rays = camera.ray(pixels)
    if np.any(rays[:, 1] * plane_y <= 1e-9):  # parallel, or the plane is behind the ray
        return None
    hits: FloatArray = rays * (plane_y / rays[:, 1])[:, None]
    if np.any(np.linalg.norm(hits, axis=1) > MAX_DISTANCE_M):
        return None
    return hits


def height_above(camera: PinholeCamera, base: FloatArray, top_pixel: FloatArray) -> float:
    """Height above `base` of the point on the vertical through `base` seen at `top_pixel`."""
    ray = camera.ray(top_pixel)[0]
    up = np.array([0.0, 1.0, 0.0])
    # Closest points of the line s * ray and the line base + h * up.
    a = np.array([[ray @ ray, -(ray @ up)], [ray @ up, -(up @ up)]])
    rhs = np.array([ray @ base, up @ base])
    _, h = np.linalg.solve(a, rhs)
    return float(h)
