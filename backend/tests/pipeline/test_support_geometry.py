"""The floor holds up from below only what stands below its horizon (supports stages)."""

from __future__ import annotations

from pathlib import Path

import numpy as np
from holiscene.geometry.camera import PinholeCamera
from holiscene.inputs import read_input_folder
from holiscene.pipeline.stages.supports import off_the_floor
from holiscene.services.reconstruction import reconstruct_scene

LEVEL = PinholeCamera(np.array([[500.0, 0, 320], [0, 500.0, 240], [0, 0, 1]]), 0.0, 0.0)


def test_a_bottom_edge_above_the_horizon_is_off_the_floor() -> None:
    high, low = [100.0, 40.0, 200.0, 120.0], [100.0, 300.0, 200.0, 420.0]
    assert off_the_floor(LEVEL, [high, low], 480) == [True, False]


def test_the_horizon_moves_with_the_pitch() -> None:
    # Pitched down 20 degrees the horizon is at y = 240 - 500 tan 20 = 58; up, at 422.
    down = PinholeCamera(LEVEL.K, 20.0, 0.0)
    assert off_the_floor(down, [[100.0, 0.0, 200.0, 40.0], [300.0, 0.0, 400.0, 80.0]], 480) == [
        True,
        False,
    ]
    up = PinholeCamera(LEVEL.K, -20.0, 0.0)
    assert off_the_floor(up, [[100.0, 300.0, 200.0, 400.0]], 480) == [True]


def test_a_box_just_below_may_hide_the_real_bottom_edge() -> None:
    wardrobe = [100.0, 20.0, 200.0, 200.0]  # its bottom hidden by the shelf in front
    shelf_in_front = [80.0, 205.0, 260.0, 400.0]
    far_aside = [400.0, 205.0, 500.0, 400.0]
    assert off_the_floor(LEVEL, [wardrobe, shelf_in_front], 480) == [False, False]
    assert off_the_floor(LEVEL, [wardrobe, far_aside], 480) == [True, False]


def test_without_a_camera_nothing_is_ruled_out() -> None:
    assert off_the_floor(None, [[100.0, 40.0, 200.0, 120.0]], 480) == [False]


def test_a_region_high_on_a_real_wall_is_not_stood_on_the_floor(real_photos: Path) -> None:
    """im3d-3's o13 (the dataset's "void", top left, bottom edge well above the horizon):
    the Relation Network said floor; placement then had no 3D box for it."""
    scene = reconstruct_scene(
        read_input_folder(real_photos / "im3d-3"), name="im3d-3", image_file="img.jpg"
    ).scene
    support = next(s for s in scene.supports if s.child == "o13")
    assert (support.parent, support.type) == ("wall", "behind")
    assert next(o for o in scene.objects if o.id == "o13").box_3d is not None
