"""Intersection over union of 3D boxes that may turn about the vertical axis (yaw only).

Boxes are given by their 8 corners in the contract's order (bottom face first), so this
works for any producer. The footprints are convex polygons in the x-z plane; their overlap
is found by clipping one with the other, and the vertical overlap multiplies it.
"""

from __future__ import annotations

import numpy as np
from numpy.typing import NDArray

from ..geometry.camera import PinholeCamera

Polygon = NDArray[np.float64]  # (N, 2), counter-clockwise


def polygon_area(poly: Polygon) -> float:
    if len(poly) < 3:
        return 0.0
    x, z = poly[:, 0], poly[:, 1]
    return float(0.5 * (np.dot(x, np.roll(z, -1)) - np.dot(z, np.roll(x, -1))))


def _counter_clockwise(poly: Polygon) -> Polygon:
    return poly if polygon_area(poly) >= 0 else poly[::-1]


def clip_convex(subject: Polygon, clip: Polygon) -> Polygon:
    """The intersection of two convex counter-clockwise polygons (Sutherland-Hodgman)."""
    output = list(subject)
    for i in range(len(clip)):
        a, b = clip[i], clip[(i + 1) % len(clip)]
        edge = b - a
        inputs, output = output, []
        if not inputs:
            break

        def inside(
            p: NDArray[np.float64], a: NDArray[np.float64] = a, edge: NDArray[np.float64] = edge
        ) -> bool:
            return bool(edge[0] * (p[1] - a[1]) - edge[1] * (p[0] - a[0]) >= -1e-12)

        for j in range(len(inputs)):
            current, previous = inputs[j], inputs[j - 1]
            if inside(current):
                if not inside(previous):
                    output.append(_line_cross(previous, current, a, b))
                output.append(current)
            elif inside(previous):
                output.append(_line_cross(previous, current, a, b))
    return np.array(output, dtype=float).reshape(-1, 2)


def _line_cross(
    p: NDArray[np.float64], q: NDArray[np.float64], a: NDArray[np.float64], b: NDArray[np.float64]
) -> NDArray[np.float64]:
    d1, d2 = q - p, b - a
    denom = d1[0] * d2[1] - d1[1] * d2[0]
    if abs(denom) < 1e-15:
        return q
    t = ((a[0] - p[0]) * d2[1] - (a[1] - p[1]) * d2[0]) / denom
    result: NDArray[np.float64] = p + t * d1
    return result


def box_volume(corners: NDArray[np.float64]) -> float:
    footprint = _counter_clockwise(corners[:4][:, [0, 2]])
    return abs(polygon_area(footprint)) * float(corners[:, 1].max() - corners[:, 1].min())


def iou_3d(corners_a: NDArray[np.float64], corners_b: NDArray[np.float64]) -> float:
    """3D IoU of two boxes given as (8, 3) corners with horizontal bottom and top faces."""
    a, b = np.asarray(corners_a, dtype=float), np.asarray(corners_b, dtype=float)
    height = min(a[:, 1].max(), b[:, 1].max()) - max(a[:, 1].min(), b[:, 1].min())
    if height <= 0:
        return 0.0
    overlap = clip_convex(
        _counter_clockwise(a[:4][:, [0, 2]]), _counter_clockwise(b[:4][:, [0, 2]])
    )
    inter = abs(polygon_area(overlap)) * height
    union = box_volume(a) + box_volume(b) - inter
    return float(inter / union) if union > 0 else 0.0


def iou_2d(a: list[float], b: list[float]) -> float:
    """IoU of two [x1, y1, x2, y2] boxes."""
    w = min(a[2], b[2]) - max(a[0], b[0])
    h = min(a[3], b[3]) - max(a[1], b[1])
    if w <= 0 or h <= 0:
        return 0.0
    inter = w * h
    union = (a[2] - a[0]) * (a[3] - a[1]) + (b[2] - b[0]) * (b[3] - b[1]) - inter
    return inter / union if union > 0 else 0.0


def _inside_box(corners: NDArray[np.float64], points: NDArray[np.float64]) -> NDArray[np.bool_]:
    """Which points lie in the box of (8, 3) corners (contract order: corner 0, its two
    bottom neighbours 1 and 3, and 4 above it)."""
    origin = corners[0]
    inside = np.ones(len(points), dtype=bool)
    for neighbour in (corners[1], corners[3], corners[4]):
        axis = neighbour - origin
        t = (points - origin) @ axis / float(axis @ axis)
        inside &= (t >= 0.0) & (t <= 1.0)
    return inside


def iou_3d_in_view(
    corners_a: NDArray[np.float64],
    corners_b: NDArray[np.float64],
    camera: PinholeCamera,
    image_size: tuple[int, int],
    cells: int = 64,
) -> float:
    """3D IoU of the parts of two boxes the photo shows (inside the camera's view frustum),
    on a regular grid of `cells`^3 points over both boxes (the room parts out of view, such
    as the wall behind the camera, are left to priors and do not count here)."""
    a, b = np.asarray(corners_a, dtype=float), np.asarray(corners_b, dtype=float)
    both = np.vstack([a, b])
    axes = [np.linspace(lo, hi, cells) for lo, hi in zip(both.min(0), both.max(0), strict=True)]
    points = np.stack(np.meshgrid(*axes, indexing="ij"), axis=-1).reshape(-1, 3)
    pixels = camera.project(points)
    width, height = image_size
    in_view = (
        np.isfinite(pixels).all(axis=1)
        & (pixels[:, 0] >= 0)
        & (pixels[:, 0] <= width)
        & (pixels[:, 1] >= 0)
        & (pixels[:, 1] <= height)
    )
    in_a = _inside_box(a, points) & in_view
    in_b = _inside_box(b, points) & in_view
    union = int(np.count_nonzero(in_a | in_b))
    return int(np.count_nonzero(in_a & in_b)) / union if union else 0.0
