"""Depth as 3D points: back-projection with K, normals from neighbouring points, planes fitted
robustly, and the camera's pitch and roll from the floor's normal.

Points are in the OpenCV camera frame (x right, y down, z forward, metres) unless a function
says otherwise; depth is along the optical axis, 0 where there is none.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from .camera import FloatArray

# Grid neighbours further apart in depth than this share of their depth straddle a depth
# edge, where a normal would mix two surfaces (a floor far away changes faster than this
# only at grazing angles no plane fit needs).
MAX_RELATIVE_JUMP = 0.25


@dataclass(frozen=True)
class PointGrid:
    """Back-projected points on a regular pixel grid, with a normal where one is defined."""

    points: FloatArray  # (N, 3) OpenCV camera frame, metres
    normals: FloatArray  # (N, 3) unit, facing the camera; NaN where undefined
    pixels: FloatArray  # (N, 2) column, row


def back_project(depth: np.ndarray, K: FloatArray, pixels: FloatArray) -> FloatArray:
    """OpenCV-frame points (N, 3) of pixels given by their integer column and row (N, 2);
    rows with no depth are NaN. A pixel's ray passes through its centre, (column + 0.5,
    row + 0.5), as in the renderer and the Surface Network's map."""
    cols, rows = pixels[:, 0].astype(int), pixels[:, 1].astype(int)
    z = depth[rows, cols].astype(float)
    centres = np.column_stack([cols + 0.5, rows + 0.5, np.ones(len(pixels))])
    homogeneous = centres @ np.linalg.inv(K).T
    points: FloatArray = homogeneous / homogeneous[:, 2:3] * z[:, None]
    points[z <= 0] = np.nan
    return points


def point_grid(depth: np.ndarray, K: FloatArray, step: int) -> PointGrid:
    """Every `step`-th pixel's point and its normal from the grid neighbours' cross product."""
    height, width = depth.shape
    rows, cols = np.mgrid[0:height:step, 0:width:step]
    pixels = np.column_stack([cols.ravel(), rows.ravel()]).astype(float)
    grid = back_project(depth, K, pixels).reshape((*rows.shape, 3))
    normals = np.full_like(grid, np.nan)
    along_x = grid[1:-1, 2:] - grid[1:-1, :-2]
    along_y = grid[2:, 1:-1] - grid[:-2, 1:-1]
    cross = np.cross(along_x, along_y)
    length = np.linalg.norm(cross, axis=2, keepdims=True)
    inner = grid[1:-1, 1:-1]
    jump = np.maximum(np.abs(along_x[..., 2]), np.abs(along_y[..., 2]))
    smooth = jump < MAX_RELATIVE_JUMP * inner[..., 2]
    with np.errstate(invalid="ignore", divide="ignore"):
        unit = cross / length
    unit[~smooth] = np.nan
    # Visible surfaces face the camera: n . p < 0.
    facing = np.einsum("ijk,ijk->ij", unit, inner) > 0
    unit[facing] *= -1
    normals[1:-1, 1:-1] = unit
    keep = np.isfinite(grid[..., 2]).ravel()
    return PointGrid(grid.reshape(-1, 3)[keep], normals.reshape(-1, 3)[keep], pixels[keep])


@dataclass(frozen=True)
class Plane:
    normal: FloatArray  # unit
    offset: float  # normal . p + offset = 0

    def distances(self, points: FloatArray) -> FloatArray:
        result: FloatArray = points @ self.normal + self.offset
        return result


def fit_plane_lsq(points: FloatArray, towards: FloatArray) -> Plane:
    """The least-squares plane of points, its normal on the side of `towards`."""
    centre = points.mean(axis=0)
    normal = np.linalg.svd(points - centre, full_matrices=False)[2][-1]
    if normal @ towards < 0:
        normal = -normal
    return Plane(normal, -float(normal @ centre))


def fit_plane_ransac(
    points: FloatArray,
    towards: FloatArray,
    threshold: float | FloatArray,
    iterations: int = 200,
    seed: int = 0,
) -> tuple[Plane, np.ndarray]:
    """The plane most points lie within `threshold` of (three-point RANSAC, refined by least
    squares on its inliers), and the inlier mask; `threshold` may be one per point."""
    rng = np.random.default_rng(seed)
    best = np.zeros(len(points), dtype=bool)
    for _ in range(iterations):
        sample = points[rng.choice(len(points), 3, replace=False)]
        normal = np.cross(sample[1] - sample[0], sample[2] - sample[0])
        norm = np.linalg.norm(normal)
        if norm < 1e-9:
            continue
        normal /= norm
        inliers = np.abs((points - sample[0]) @ normal) < threshold
        if inliers.sum() > best.sum():
            best = inliers
    plane = fit_plane_lsq(points[best], towards)
    inliers = np.abs(plane.distances(points)) < threshold
    return fit_plane_lsq(points[inliers], towards), inliers


def pitch_roll_from_up(up_cv: FloatArray) -> tuple[float, float]:
    """Pitch and roll (degrees, `geometry.camera`'s convention) of a camera that sees the
    world's up direction as `up_cv` (OpenCV frame): up_cv = (-sin r cos p, -cos r cos p,
    -sin p)."""
    up = up_cv / np.linalg.norm(up_cv)
    pitch = math.asin(float(np.clip(-up[2], -1.0, 1.0)))
    roll = math.atan2(float(-up[0]), float(-up[1]))
    return math.degrees(pitch), math.degrees(roll)


def level_clusters(values: FloatArray, bin_size: float, min_count: int) -> list[float]:
    """Centres of the histogram bins of `values` holding at least `min_count` of them, in
    increasing order: the levels of parallel planes (floor and table tops, wall and the
    furniture before it)."""
    if len(values) == 0:
        return []
    low = float(values.min())
    bins = np.floor((values - low) / bin_size).astype(int)
    counts = np.bincount(bins)
    return [low + (i + 0.5) * bin_size for i in np.flatnonzero(counts >= min_count)]
