"""The room's three orthogonal directions (a Manhattan frame) and the camera's pitch and roll,
estimated jointly from line segments (thesis Ch. 4.4.1, Eq. 4.2, in a calibrated form).

Each segment and the camera centre span an "interpretation plane"; a 3D line of direction d
lies in it exactly when the plane's normal n is orthogonal to d. With K known, the vertical
direction fixes pitch and roll, and one angle (the room's yaw) fixes both horizontal
directions. So: vertical vanishing point by RANSAC -> pitch and roll; a 1D search over yaw ->
the horizontal directions; then alternate assigning segments to directions and refining
(pitch, roll, yaw) by Gauss-Newton on the residuals n . d, like the thesis's K-means-style
re-estimation of the vanishing points.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

from .camera import FloatArray, PinholeCamera, pitch_roll_from_up_direction
from .lines import Segments
from .vanishing import vertical_candidates

INLIER_SINE = math.sin(math.radians(1.5))
# Indoor photos: the camera looks at most this far up or down, and is at most this tilted.
PLAUSIBLE_PITCH_DEG = (-25.0, 55.0)
PLAUSIBLE_ROLL_DEG = 25.0
NO_FAMILY = -1
FAMILIES = ("vertical", "room_x", "room_z")


@dataclass(frozen=True)
class ManhattanFrame:
    pitch_deg: float
    roll_deg: float
    yaw_deg: float  # the room's x axis turned about +y from the camera's heading, in (-45, 45]
    family: NDArray[np.int64]  # per segment: index into FAMILIES, or NO_FAMILY
    support: FloatArray  # total inlier segment length per family (pixels)

    def directions(self) -> FloatArray:
        """World directions (3, 3): vertical, room x, room z."""
        return room_directions(self.yaw_deg)

    def vanishing_points(self, K: FloatArray) -> FloatArray:
        """Homogeneous image points (3, 3) of the three directions, unit-normalised rows."""
        camera = PinholeCamera(K, self.pitch_deg, self.roll_deg)
        points = (K @ camera.world_from_cv.T @ self.directions().T).T
        result: FloatArray = points / np.linalg.norm(points, axis=1, keepdims=True)
        return result


def room_directions(yaw_deg: float) -> FloatArray:
    c, s = math.cos(math.radians(yaw_deg)), math.sin(math.radians(yaw_deg))
    return np.array([[0.0, 1.0, 0.0], [c, 0.0, -s], [s, 0.0, c]])


def plane_normals_cv(segments: Segments, K: FloatArray) -> FloatArray:
    """Unit normals of the segments' interpretation planes, OpenCV camera frame."""
    k_inv = np.linalg.inv(K)
    ones = np.ones((len(segments.endpoints), 1))
    p = np.hstack([segments.endpoints[:, :2], ones]) @ k_inv.T
    q = np.hstack([segments.endpoints[:, 2:], ones]) @ k_inv.T
    n = np.cross(p, q)
    result: FloatArray = n / np.maximum(np.linalg.norm(n, axis=1, keepdims=True), 1e-12)
    return result


def _residuals(normals_cv: FloatArray, K: FloatArray, params: FloatArray) -> FloatArray:
    """|n . d| of every segment against every direction: (N, 3)."""
    pitch, roll, yaw = params
    world_normals = normals_cv @ PinholeCamera(K, pitch, roll).world_from_cv.T
    result: FloatArray = np.abs(world_normals @ room_directions(yaw).T)
    return result


def _best_yaw(residual_to_horizontal: FloatArray, lengths: FloatArray) -> float:
    """Grid search of the room yaw (the horizontal frame has a 90-degree symmetry)."""
    best_yaw, best_score = 0.0, -1.0
    for yaw in np.arange(-45.0, 45.0, 0.25):
        dirs = room_directions(float(yaw))[1:]
        hits = np.abs(residual_to_horizontal @ dirs.T) < INLIER_SINE
        score = float((lengths[:, None] * hits).sum())
        if score > best_score:
            best_yaw, best_score = float(yaw), score
    return best_yaw


def _support(residuals: FloatArray, lengths: FloatArray) -> float:
    return float(lengths[residuals.min(axis=1) < INLIER_SINE].sum())


def _canonical_yaw(yaw: float) -> float:
    return (yaw + 45.0) % 90.0 - 45.0 if (yaw + 45.0) % 90.0 != 0 else 45.0


def estimate_manhattan_frame(
    segments: Segments, K: FloatArray, rounds: int = 4
) -> ManhattanFrame | None:
    """None when the photo shows too few vertical lines to fix pitch and roll."""

    def plausible(candidate: FloatArray) -> bool:
        pitch, roll = pitch_roll_from_up_direction(np.linalg.solve(K, candidate).astype(np.float64))
        low, high = PLAUSIBLE_PITCH_DEG
        return low <= pitch <= high and abs(roll) <= PLAUSIBLE_ROLL_DEG

    candidates = vertical_candidates(segments, plausible=plausible)
    if not candidates:
        return None
    normals = plane_normals_cv(segments, K)
    lengths = segments.lengths
    # Several vertical hypotheses (texture lines can outvote true verticals): keep the one
    # whose whole frame, with its best yaw, explains the most segment length.
    best: tuple[float, FloatArray] | None = None
    for vp in candidates:
        pitch, roll = pitch_roll_from_up_direction(np.linalg.solve(K, vp).astype(np.float64))
        world_normals = normals @ PinholeCamera(K, pitch, roll).world_from_cv.T
        yaw = _best_yaw(world_normals, lengths)
        total = _support(_residuals(normals, K, np.array([pitch, roll, yaw])), lengths)
        if best is None or total > best[0]:
            best = (total, np.array([pitch, roll, yaw]))
    assert best is not None
    params = best[1]
    family = np.full(len(lengths), NO_FAMILY)
    for _ in range(rounds):
        residuals = _residuals(normals, K, params)
        family = np.where(residuals.min(axis=1) < INLIER_SINE, residuals.argmin(axis=1), NO_FAMILY)
        params = _refine(normals, K, params, family, lengths)
    residuals = _residuals(normals, K, params)
    family = np.where(residuals.min(axis=1) < INLIER_SINE, residuals.argmin(axis=1), NO_FAMILY)
    support = np.array([lengths[family == f].sum() for f in range(3)])
    return ManhattanFrame(
        pitch_deg=float(params[0]),
        roll_deg=float(params[1]),
        yaw_deg=_canonical_yaw(float(params[2])),
        family=family,
        support=support,
    )


def _refine(
    normals: FloatArray,
    K: FloatArray,
    params: FloatArray,
    family: NDArray[np.int64],
    lengths: FloatArray,
    iterations: int = 5,
) -> FloatArray:
    """Gauss-Newton on sqrt(length) * (n . d_family) over the assigned segments."""
    assigned = family != NO_FAMILY
    if assigned.sum() < 6:
        return params
    n, f, w = normals[assigned], family[assigned], np.sqrt(lengths[assigned])

    def signed(p: FloatArray) -> FloatArray:
        world = n @ PinholeCamera(K, p[0], p[1]).world_from_cv.T
        dirs = room_directions(p[2])[f]
        result: FloatArray = w * np.einsum("ij,ij->i", world, dirs)
        return result

    damping = 1e-3
    r = signed(params)
    for _ in range(iterations):
        step = 1e-4
        jac = np.column_stack([(signed(params + step * e) - r) / step for e in np.eye(3)])
        # Levenberg-Marquardt: take the step only if it lowers the cost.
        normal = jac.T @ jac
        delta = np.linalg.solve(normal + damping * np.diag(np.diag(normal) + 1e-9), -jac.T @ r)
        trial = params + delta
        r_trial = signed(trial)
        if r_trial @ r_trial < r @ r:
            params, r, damping = trial, r_trial, damping * 0.3
        else:
            damping *= 10.0
        if np.abs(delta).max() < 1e-6:
            break
    return params
