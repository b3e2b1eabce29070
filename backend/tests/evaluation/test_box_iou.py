"""3D and 2D IoU on hand-computed cases."""

from __future__ import annotations

import math

import numpy as np
import pytest
from holiscene.evaluation.box_iou import iou_2d, iou_3d, iou_3d_in_view
from holiscene.geometry.boxes import box_corners
from holiscene.geometry.camera import PinholeCamera
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


def test_in_view_iou_ignores_what_the_camera_cannot_see() -> None:
    """Two rooms that differ only behind the camera: the full IoU sees the difference, the
    in-view IoU does not; moving the wall the camera faces changes both."""
    camera = PinholeCamera(np.array([[400.0, 0, 320], [0, 400, 240], [0, 0, 1]]), 10.0, 0.0)
    size = (640, 480)
    # The camera looks along +x (y up, z right); the room spans x from -back to 5.
    room = box_corners(np.array([2.0, 0.0, 0.0]), np.array([6.0, 3.0, 4.0]), 0.0)  # back 1 m
    deeper_behind = box_corners(np.array([1.5, 0.0, 0.0]), np.array([7.0, 3.0, 4.0]), 0.0)
    assert iou_3d(room, deeper_behind) == pytest.approx(6 / 7)
    assert iou_3d_in_view(room, deeper_behind, camera, size) == pytest.approx(1.0)
    assert iou_3d_in_view(room, room, camera, size) == pytest.approx(1.0)
    shallower = box_corners(np.array([1.5, 0.0, 0.0]), np.array([5.0, 3.0, 4.0]), 0.0)
    in_view = iou_3d_in_view(room, shallower, camera, size)
    assert 0.5 < in_view < 0.95
    assert iou_3d_in_view(room, shallower, camera, size, cells=96) == pytest.approx(
        in_view, abs=0.02
    )
