"""Line support along a room's projected edges: length counted only along the edge, only for
segments of the edge's family, and only for the part of an edge in front of the camera."""

from __future__ import annotations

import numpy as np
import pytest
from holiscene.geometry.camera import FloatArray, PinholeCamera
from holiscene.geometry.lines import Segments
from holiscene.geometry.room_layout import _edge_score

Edge = tuple[FloatArray, FloatArray, int]
CAMERA = PinholeCamera(np.array([[400.0, 0, 320], [0, 400, 240], [0, 0, 1]]), 10.0, 0.0)
TOLERANCE = 3.0
FLOOR_EDGE: Edge = (np.array([4.0, -1.0, -1.0]), np.array([4.0, -1.0, 1.0]), 2)  # across the view


def score(endpoints: list[list[float]], family: list[int], edges: list[Edge]) -> float:
    segments = Segments(np.array(endpoints, dtype=float))
    return _edge_score(CAMERA, segments, np.array(family), edges, TOLERANCE)


def test_a_segment_on_the_edge_counts_its_length_and_no_other_does() -> None:
    a, b = CAMERA.project(np.array(FLOOR_EDGE[:2]))
    on_edge = [*a, *b]
    beside = [a[0], a[1] + 2 * TOLERANCE, b[0], b[1] + 2 * TOLERANCE]
    half = [*a, *((a + b) / 2)]
    assert score([on_edge], [2], [FLOOR_EDGE]) == pytest.approx(np.hypot(*(b - a)))
    assert score([half], [2], [FLOOR_EDGE]) == pytest.approx(np.hypot(*(b - a)) / 2)
    assert score([beside], [2], [FLOOR_EDGE]) == 0.0
    assert score([on_edge], [1], [FLOOR_EDGE]) == 0.0  # another family's segment


def test_only_the_part_of_an_edge_in_front_of_the_camera_counts() -> None:
    behind = (np.array([-3.0, -1.0, -1.0]), np.array([-3.0, -1.0, 1.0]), 2)
    assert score([[0, 0, 640, 480]], [2], [behind]) == 0.0
    # A floor edge running from behind the camera to 4 m ahead: a segment along its image
    # counts as it does for the edge's part ahead of the camera.
    through = (np.array([-2.0, -1.0, 1.0]), np.array([4.0, -1.0, 1.0]), 1)
    ahead = (np.array([0.5, -1.0, 1.0]), through[1], 1)
    a, b = CAMERA.project(np.array([ahead[0], ahead[1]]))
    on_image = [[*a, *b]]
    assert score(on_image, [1], [through]) == pytest.approx(score(on_image, [1], [ahead]))
    assert score(on_image, [1], [through]) == pytest.approx(np.hypot(*(b - a)))
