"""The vertical vanishing point, found by RANSAC over near-vertical line segments."""

from __future__ import annotations

import math

import numpy as np

from .camera import FloatArray
from .lines import Segments


def _angular_residuals(segments: Segments, vp: FloatArray) -> FloatArray:
    """Angle (radians) between each segment and the line from its midpoint to the point."""
    mids = segments.midpoints
    # Direction from midpoint to a homogeneous point (works for points at infinity too).
    to_vp = vp[:2][None, :] - mids * vp[2]
    norm = np.maximum(np.linalg.norm(to_vp, axis=1), 1e-12)
    cos = np.abs(np.sum(to_vp * segments.directions, axis=1)) / norm
    result: FloatArray = np.arccos(np.clip(cos, 0.0, 1.0))
    return result


def _fit_point(lines: FloatArray, weights: FloatArray) -> FloatArray:
    """Least-squares common point of weighted homogeneous lines (smallest singular vector)."""
    _, _, vt = np.linalg.svd(lines * weights[:, None])
    result: FloatArray = vt[-1]
    return result / np.linalg.norm(result)


def vertical_vanishing_point(
    segments: Segments,
    *,
    max_tilt_deg: float = 30.0,
    inlier_deg: float = 1.5,
    iterations: int = 400,
    min_inliers: int = 4,
    seed: int = 0,
) -> FloatArray | None:
    """Homogeneous vertical vanishing point, or None when the photo shows too few verticals.

    Candidates are segments within `max_tilt_deg` of the image's vertical axis; a pair of them
    proposes a point and the point with the largest inlier length wins, then it is refined on
    its inliers. The returned point is unit-normalised (it may lie at infinity).
    """
    tilt = np.degrees(np.arccos(np.clip(np.abs(segments.directions[:, 1]), 0.0, 1.0)))
    candidates = segments.subset(tilt <= max_tilt_deg)
    if len(candidates.endpoints) < min_inliers:
        return None
    lines = candidates.homogeneous_lines()
    lengths = candidates.lengths
    rng = np.random.default_rng(seed)
    threshold = math.radians(inlier_deg)
    probs = lengths / lengths.sum()
    best_score, best_inliers = 0.0, None
    for _ in range(iterations):
        i, j = rng.choice(len(lines), size=2, replace=False, p=probs)
        vp = np.cross(lines[i], lines[j])
        if not np.any(vp):
            continue
        inliers = _angular_residuals(candidates, vp) < threshold
        score = float(lengths[inliers].sum())
        if score > best_score:
            best_score, best_inliers = score, inliers
    if best_inliers is None or int(best_inliers.sum()) < min_inliers:
        return None
    return _fit_point(lines[best_inliers], lengths[best_inliers])
