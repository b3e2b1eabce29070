"""Surface labels: the true map of a synthetic room, a room hypothesis's own labels, and how
the Surface Network's map scores hypotheses."""

from __future__ import annotations

from functools import cache

import numpy as np
import pytest
from holiscene.geometry.camera import PinholeCamera
from holiscene.geometry.room_layout import RoomHypothesis
from holiscene.geometry.surface_labels import (
    CEILING,
    CLASS_OF_SURFACE,
    FLOOR,
    MAP_SIZE,
    SURFACE_CLASSES,
    map_pixels,
    nearest_surface,
    true_surface_map,
)
from holiscene.geometry.surface_map import SurfaceMap
from holiscene.synth.generate import SyntheticScene, synthesize

SEEDS = (4200, 4201, 4202)


@cache
def scene(seed: int) -> SyntheticScene:
    return synthesize(seed)


def _true_room(synthetic: SyntheticScene) -> tuple[PinholeCamera, np.ndarray, RoomHypothesis]:
    """The true camera, room axes and room box (camera heights) of a synthetic scene."""
    truth = synthetic.truth
    assert truth.camera is not None and truth.layout.corners_3d is not None
    camera = PinholeCamera(synthetic.K, truth.camera.pitch_deg or 0.0, truth.camera.roll_deg or 0.0)
    corners = np.array(truth.layout.corners_3d)
    x_axis = corners[1] - corners[0]
    if abs(x_axis[0]) / np.linalg.norm(x_axis) < 0.7:  # room x is the axis nearer the heading
        x_axis = corners[3] - corners[0]
    x_axis = x_axis / np.linalg.norm(x_axis) * np.sign(x_axis[0])
    to_room = np.column_stack([x_axis, [0.0, 1.0, 0.0], np.cross(x_axis, [0.0, 1.0, 0.0])])
    local = corners @ to_room / truth.camera.height_m
    low, high = local.min(axis=0), local.max(axis=0)
    assert low[1] == pytest.approx(-1.0, abs=1e-6)  # the floor is one camera height down
    room = RoomHypothesis(high[0], -low[2], high[2], -low[0], high[1], 0.0, True)
    return camera, to_room, room


@pytest.mark.parametrize("seed", SEEDS)
def test_true_map_is_the_true_room_seen_through_the_camera(seed: int) -> None:
    synthetic = scene(seed)
    labels = true_surface_map(synthetic.truth)
    assert labels.shape == (MAP_SIZE[1], MAP_SIZE[0])
    assert set(np.unique(labels)) <= set(range(len(SURFACE_CLASSES)))
    # Cameras look level or down: some floor is seen, and it is below any ceiling.
    rows_with_ceiling = np.nonzero((labels == CEILING).any(axis=1))[0]
    rows_with_floor = np.nonzero((labels == FLOOR).any(axis=1))[0]
    if len(rows_with_ceiling):
        assert rows_with_ceiling.max() < rows_with_floor.min()
    # The same room as a hypothesis labels the cells the same way.
    camera, to_room, room = _true_room(synthetic)
    width, height = synthetic.truth.image.width, synthetic.truth.image.height
    rays = camera.ray(map_pixels(width, height)) @ to_room
    assert (CLASS_OF_SURFACE[room.surfaces_seen(rays)] == labels.ravel()).all()


def test_nearest_surface_of_axis_rays() -> None:
    rays = np.array([[1.0, 0, 0], [-1, 0, 0], [0, 0, -1], [0, 0, 1], [0, -1, 0], [0, 1, 0]])
    assert nearest_surface(rays, 3, 1, 2, 2, 1, 1.5).tolist() == [0, 1, 2, 3, 4, 5]
    # A ray to a corner region meets the nearer face.
    assert nearest_surface(np.array([[1.0, -1.0, 0.0]]), 3, 1, 2, 2, 1, 1.5).tolist() == [4]


def test_agreement_prefers_the_true_room() -> None:
    synthetic = scene(SEEDS[0])
    camera, to_room, room = _true_room(synthetic)
    width, height = synthetic.truth.image.width, synthetic.truth.image.height
    rays = camera.ray(map_pixels(width, height)) @ to_room
    one_hot = np.eye(len(SURFACE_CLASSES), dtype=np.float32)[
        true_surface_map(synthetic.truth).ravel()
    ]
    surface_map = SurfaceMap(one_hot, rays)
    assert surface_map.agreement(room.surfaces_seen(rays)) == pytest.approx(1.0)
    for wall in ("front", "left", "right"):
        moved = RoomHypothesis(**{**room.__dict__, wall: getattr(room, wall) * 0.6})
        assert surface_map.agreement(moved.surfaces_seen(rays)) < 1.0
