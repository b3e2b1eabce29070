"""Camera geometry: projection and back-projection agree; pitch and roll come back from lines."""

from __future__ import annotations

import math

import numpy as np
from holiscene.geometry.boxes import box_corners
from holiscene.geometry.camera import (
    PinholeCamera,
    default_intrinsics,
    pitch_roll_from_up_direction,
)
from holiscene.geometry.lines import Segments
from holiscene.geometry.vanishing import vertical_candidates
from hypothesis import given, settings
from hypothesis import strategies as st

angles = st.floats(min_value=-40, max_value=40, allow_nan=False)


@settings(max_examples=60, deadline=None)
@given(pitch=angles, roll=angles, x=st.floats(1, 10), y=st.floats(-2, 2), z=st.floats(-3, 3))
def test_project_then_back_project(pitch: float, roll: float, x: float, y: float, z: float) -> None:
    camera = PinholeCamera(default_intrinsics(640, 480), pitch, roll)
    point = np.array([[x, y, z]])
    pixel = camera.project(point)
    if np.isnan(pixel).any():
        return  # behind the camera
    ray = camera.ray(pixel)[0]
    assert np.allclose(ray, point[0] / np.linalg.norm(point[0]), atol=1e-9)


@settings(max_examples=60, deadline=None)
@given(pitch=angles, roll=angles)
def test_pitch_and_roll_from_world_up(pitch: float, roll: float) -> None:
    camera = PinholeCamera(np.eye(3), pitch, roll)
    up_cv = camera.world_from_cv.T @ np.array([0.0, 1.0, 0.0])
    got_pitch, got_roll = pitch_roll_from_up_direction(up_cv)
    assert math.isclose(got_pitch, pitch, abs_tol=1e-9)
    assert math.isclose(got_roll, roll, abs_tol=1e-9)


def test_pitch_sign_convention() -> None:
    """Looking down, the optical axis points below the horizon (negative world y)."""
    camera = PinholeCamera(default_intrinsics(640, 480), 20.0, 0.0)
    centre_ray = camera.ray(np.array([[320.0, 240.0]]))[0]
    assert math.isclose(centre_ray[1], -math.sin(math.radians(20.0)))
    assert centre_ray[0] > 0


@settings(max_examples=25, deadline=None)
@given(pitch=st.floats(-25, 25), roll=st.floats(-10, 10), seed=st.integers(0, 1000))
def test_vertical_vanishing_point_recovers_pitch_and_roll(
    pitch: float, roll: float, seed: int
) -> None:
    """Project vertical edges of random boxes in front of the camera; recover the angles."""
    rng = np.random.default_rng(seed)
    K = default_intrinsics(640, 480)
    camera = PinholeCamera(K, pitch, roll)
    segments = []
    for _ in range(12):
        base = np.array([rng.uniform(3, 8), rng.uniform(-1.5, -0.5), rng.uniform(-2, 2)])
        top = base + np.array([0.0, rng.uniform(0.6, 1.5), 0.0])
        ends = camera.project(np.array([base, top]))
        if not np.isnan(ends).any():
            segments.append(ends.reshape(-1))
    found = vertical_candidates(Segments(np.array(segments)), count=1)
    assert found
    vp = found[0]
    got_pitch, got_roll = pitch_roll_from_up_direction(np.linalg.solve(K, vp))
    assert abs(got_pitch - pitch) < 0.05
    assert abs(got_roll - roll) < 0.05


def test_box_corners_follow_the_contract_order() -> None:
    corners = box_corners(np.array([1.0, 2.0, 3.0]), np.array([2.0, 4.0, 6.0]), 0.0)
    assert corners.tolist()[0] == [0.0, 0.0, 0.0]
    assert corners.tolist()[6] == [2.0, 4.0, 6.0]
    turned = box_corners(np.zeros(3), np.array([2.0, 2.0, 2.0]), 90.0)
    # yaw 90 turns the box's front (+x) to -z: the (+x, -y, -z) corner lands at (-1, -1, -1).
    assert np.allclose(turned[1], [-1.0, -1.0, -1.0])
