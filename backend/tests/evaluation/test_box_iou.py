"""3D and 2D IoU on hand-computed cases."""

from __future__ import annotations

import math

import numpy as np
import pytest
from holiscene.evaluation.box_iou import iou_2d, iou_3d
from holiscene.geometry.boxes import box_corners
from hypothesis import given, settings
from hypothesis import strategies as st


def cube(center: tuple[float, float, float], size: float = 1.0, yaw: float = 0.0) -> np.ndarray:
    return box_corners(np.array(center), np.full(3, size), yaw)


def test_unit_cubes_offset_by_half_a_side() -> None:
    assert iou_3d(cube((0, 0, 0)), cube((0.5, 0, 0))) == pytest.approx(1 / 3)


def test_identical_disjoint_and_stacked() -> None:
    assert iou_3d(cube((0, 0, 0)), cube((0, 0, 0))) == pytest.approx(1.0)
    assert iou_3d(cube((0, 0, 0)), cube((3, 0, 0))) == 0.0
    assert iou_3d(cube((0, 0, 0)), cube((0, 1.0, 0))) == 0.0  # touching faces


def test_turned_cube_inside_larger_one() -> None:
    small = cube((0, 0, 0), 1.0, 45.0)
    large = cube((0, 0, 0), 2.0)
    assert iou_3d(small, large) == pytest.approx(1 / 8)


def test_cube_turned_45_degrees_against_itself_unturned() -> None:
    # A unit square and the same square turned 45 degrees about its centre overlap in a
    # regular octagon of area 2 (sqrt 2 - 1); both cubes are 1 high.
    octagon = 2 * (math.sqrt(2) - 1)
    expected = octagon / (2 - octagon)
    assert iou_3d(cube((0, 0, 0)), cube((0, 0, 0), 1.0, 45.0)) == pytest.approx(expected)


@settings(max_examples=50, deadline=None)
@given(
    yaw=st.floats(-180, 180),
    dx=st.floats(-1.5, 1.5),
    dz=st.floats(-1.5, 1.5),
)
def test_iou_is_symmetric_and_bounded(yaw: float, dx: float, dz: float) -> None:
    a = box_corners(np.zeros(3), np.array([1.0, 0.5, 2.0]), 10.0)
    b = box_corners(np.array([dx, 0.1, dz]), np.array([0.8, 0.7, 1.2]), yaw)
    forward, backward = iou_3d(a, b), iou_3d(b, a)
    assert forward == pytest.approx(backward, abs=1e-9)
    assert 0.0 <= forward <= 1.0


def test_iou_2d() -> None:
    assert iou_2d([0, 0, 2, 2], [1, 1, 3, 3]) == pytest.approx(1 / 7)
    assert iou_2d([0, 0, 1, 1], [2, 2, 3, 3]) == 0.0
