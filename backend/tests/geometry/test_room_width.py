"""The side wall out of view: the width prior's median, the view's bound, rooms it cannot fit;
and how near a wall can be and stay out of view."""

from __future__ import annotations

import numpy as np
import pytest
from holiscene.geometry.camera import PinholeCamera
from holiscene.geometry.room_layout import RoomHypothesis
from holiscene.geometry.room_width import (
    CAMERA_ACROSS_SHARE,
    ROOM_WIDTH_RANGE_M,
    unseen_side_wall_distance,
)
from holiscene.geometry.surface_labels import map_pixels
from holiscene.synth import ranges


def test_the_prior_is_the_synthetic_rooms_own() -> None:
    """The synthetic rooms stand for the rooms people photograph: the prior follows them."""
    assert ROOM_WIDTH_RANGE_M == ranges.ROOM_WIDTH_M
    assert tuple(0.5 + share for share in ranges.CAMERA_SIDEWAYS_SHARE) == CAMERA_ACROSS_SHARE


def test_the_unseen_wall_sits_at_the_median_width_of_rooms_like_the_seen_one() -> None:
    """Draw rooms and cameras as the prior says; among those whose left wall is about 1.5 m
    away, half are narrower than the seen wall plus the returned distance."""
    rng = np.random.default_rng(0)
    widths = rng.uniform(*ROOM_WIDTH_RANGE_M, 2_000_000)
    left = widths * rng.uniform(*CAMERA_ACROSS_SHARE, len(widths))
    alike = np.abs(left - 1.5) < 0.01
    distance = unseen_side_wall_distance(1.5, 0.0)
    assert distance is not None
    assert np.mean(widths[alike] < 1.5 + distance) == pytest.approx(0.5, abs=0.02)


def test_the_unseen_wall_stays_out_of_view() -> None:
    free = unseen_side_wall_distance(2.0, 0.5)
    bound = unseen_side_wall_distance(2.0, 3.0)
    assert free is not None and bound is not None
    assert free < 3.0 <= bound


def test_rooms_the_prior_cannot_hold_keep_another_guess() -> None:
    # A wall 5 m off with the camera in the middle half of the room: over 6 m wide.
    assert unseen_side_wall_distance(5.0, 0.5) is None
    # The other wall out of view needs more than 4.5 m: over 6 m wide again.
    assert unseen_side_wall_distance(2.0, 4.5) is None


def test_a_wall_nearer_than_its_out_of_view_distance_comes_into_view() -> None:
    camera = PinholeCamera(np.array([[400.0, 0, 320], [0, 400, 240], [0, 0, 1]]), 12.0, 0.0)
    rays = camera.ray(map_pixels(640, 480))  # room axes = camera heading: no yaw
    room = RoomHypothesis(4.0, 2.0, 6.0, 0.5, 1.0, 0.0, True)
    assert "right" not in room.faces_in_view(rays)
    nearest = room.nearest_out_of_view("right", rays)
    assert "right" not in RoomHypothesis(
        4.0, 2.0, nearest * 1.001, 0.5, 1.0, 0.0, True
    ).faces_in_view(rays)
    assert "right" in RoomHypothesis(4.0, 2.0, nearest * 0.98, 0.5, 1.0, 0.0, True).faces_in_view(
        rays
    )
