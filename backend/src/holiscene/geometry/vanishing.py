"""The vertical vanishing point, found by RANSAC over near-vertical line segments."""

from __future__ import annotations

import math
from collections.abc import Callable

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


def vertical_candidates(
    segments: Segments,
    *,
    max_tilt_deg: float = 30.0,
    inlier_deg: float = 1.5,
    iterations: int = 400,
    min_inliers: int = 4,
    seed: int = 0,
    plausible: Callable[[FloatArray], bool] | None = None,
    count: int = 3,
) -> list[FloatArray]:
    """Up to `count` distinct vertical vanishing points, best first (homogeneous, unit norm);
    empty when the photo shows too few verticals.

    Candidates are segments within `max_tilt_deg` of the image's vertical axis; a pair of them
    proposes a point and the point with the largest inlier length wins, then it is refined on
    its inliers. The returned point is unit-normalised (it may lie at infinity).
    `plausible` rejects hypotheses that imply an impossible camera (e.g. floor-tile lines
    converging to the horizon, which a steep pitch could mistake for verticals).
    """
    tilt = np.degrees(np.arccos(np.clip(np.abs(segments.directions[:, 1]), 0.0, 1.0)))
    candidates = segments.subset(tilt <= max_tilt_deg)
    if len(candidates.endpoints) < min_inliers:
        return []
    lines = candidates.homogeneous_lines()
    lengths = candidates.lengths
    rng = np.random.default_rng(seed)
    threshold = math.radians(inlier_deg)
    probs = lengths / lengths.sum()
    hypotheses: list[tuple[float, np.ndarray]] = []
    for _ in range(iterations):
        i, j = rng.choice(len(lines), size=2, replace=False, p=probs)
        vp = np.cross(lines[i], lines[j])
        if not np.any(vp) or (plausible is not None and not plausible(vp)):
            continue
        inliers = _angular_residuals(candidates, vp) < threshold
        if int(inliers.sum()) >= min_inliers:
            hypotheses.append((float(lengths[inliers].sum()), inliers))
    hypotheses.sort(key=lambda h: -h[0])
    found: list[FloatArray] = []
    for _, inliers in hypotheses:
        refined = _fit_point(lines[inliers], lengths[inliers])
        if plausible is not None and not plausible(refined):
            continue
        if all(abs(float(refined @ other)) < math.cos(math.radians(2.0)) for other in found):
            found.append(refined)
        if len(found) == count:
            break
    return found
