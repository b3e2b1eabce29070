"""Chamfer distance, the EMD approximation and normal consistency on point sets of known answer."""

from __future__ import annotations

import numpy as np
import pytest
from holiscene.evaluation.shape_metrics import (
    chamfer_distance,
    emd_approximation,
    normal_consistency,
)


def _cloud(count: int = 600) -> np.ndarray:
    return np.random.default_rng(0).uniform(-0.5, 0.5, (count, 3))


def test_identical_sets_score_perfectly() -> None:
    points = _cloud(512)  # EMD_POINTS: the subsamples hold every point
    normals = np.tile([0.0, 1.0, 0.0], (len(points), 1))
    assert chamfer_distance(points, points) == pytest.approx(0.0, abs=1e-6)
    assert emd_approximation(points, points[::-1].copy()) == pytest.approx(0.0, abs=1e-9)
    assert normal_consistency(points, normals, points, -normals) == pytest.approx(1.0)


def test_a_shift_far_larger_than_the_set_costs_its_length() -> None:
    points = 0.01 * _cloud()
    moved = points + np.array([3.0, 0.0, 0.0])
    assert chamfer_distance(points, moved) == pytest.approx(3.0, rel=0.1)
    assert emd_approximation(points, moved) == pytest.approx(3.0, rel=0.05)


def test_emd_sees_what_chamfer_misses_all_points_piled_on_one_side() -> None:
    points = _cloud()
    piled = points.copy()
    piled[:, 0] = np.abs(piled[:, 0])  # the left half folded onto the right half
    assert emd_approximation(points, piled) > 2.0 * chamfer_distance(points, piled)


def test_perpendicular_normals_are_inconsistent() -> None:
    points = _cloud()
    up = np.tile([0.0, 1.0, 0.0], (len(points), 1))
    side = np.tile([1.0, 0.0, 0.0], (len(points), 1))
    assert normal_consistency(points, up, points, side) == pytest.approx(0.0)
