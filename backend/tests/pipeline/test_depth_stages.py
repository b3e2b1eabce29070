"""The depth stages on a synthetic room (exact depth.png, gt.json beside it): metric scale,
floor plane, room and boxes from the points; and the single-photo path unchanged without."""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np
import pytest
from holiscene.cli import main
from holiscene.evaluation.box_iou import iou_3d
from holiscene.geometry.camera import PinholeCamera
from holiscene.geometry.depth_points import fit_plane_ransac, pitch_roll_from_up, point_grid
from holiscene.geometry.depth_room import fit_floor
from holiscene.inputs import read_input_folder
from holiscene.pipeline import DEFAULT_STAGES
from holiscene.services.reconstruction import reconstruct_scene
from holiscene_schema import Scene

SEED = 950003  # a held-out room whose ceiling the photo shows


@pytest.fixture(scope="module")
def room(tmp_path_factory: pytest.TempPathFactory) -> Path:
    out = tmp_path_factory.mktemp("synth")
    assert main(["synth", "--seed", str(SEED), "--count", "1", "-o", str(out)]) == 0
    return out / f"synth-{SEED}"


def _truth(room: Path) -> Scene:
    return Scene.model_validate(json.loads((room / "gt.json").read_text()))


def _run(room: Path, use_depth: bool, stages: tuple[str, ...] = DEFAULT_STAGES) -> Scene:
    inputs = read_input_folder(room, use_depth=use_depth)
    return reconstruct_scene(inputs, name=room.name, image_file="img.png", stages=stages).scene


def _front_distance(corners: np.ndarray) -> float:
    """The camera's distance to the room's front wall (corners 1 and 2 are on it)."""
    axis = (corners[1] - corners[0]) / np.linalg.norm(corners[1] - corners[0])
    return float(corners[1] @ axis)


def test_pitch_and_roll_from_the_up_direction_round_trip() -> None:
    camera = PinholeCamera(np.eye(3), 14.0, -6.5)
    up_cv = camera.world_from_cv.T @ np.array([0.0, 1.0, 0.0])
    assert pitch_roll_from_up(up_cv) == pytest.approx((14.0, -6.5))


def test_ransac_finds_the_plane_among_outliers() -> None:
    rng = np.random.default_rng(3)
    plane = np.column_stack([rng.uniform(-2, 2, 300), np.full(300, 1.3), rng.uniform(1, 5, 300)])
    clutter = rng.uniform([-2, -1, 1], [2, 1.2, 5], (200, 3))
    fit, inliers = fit_plane_ransac(np.vstack([plane, clutter]), np.array([0.0, -1, 0]), 0.02)
    assert fit.normal == pytest.approx([0.0, -1.0, 0.0], abs=1e-6)
    assert fit.offset == pytest.approx(1.3, abs=1e-6)
    assert inliers[:300].all() and inliers[300:].mean() < 0.05


def test_the_floor_plane_gives_the_camera_height_pitch_and_roll(room: Path) -> None:
    truth = _truth(room).camera
    assert truth is not None and truth.height_m is not None and truth.pitch_deg is not None
    inputs = read_input_folder(room)
    assert inputs.depth is not None and inputs.K is not None
    grid = point_grid(inputs.depth.metres, inputs.K, 4)
    level = PinholeCamera(inputs.K, 0.0, 0.0)  # a guess 10-25 degrees off
    floor = fit_floor(grid, level.world_from_cv.T @ np.array([0.0, 1.0, 0.0]))
    assert floor is not None
    assert floor.camera_height == pytest.approx(truth.height_m, rel=0.02)
    assert floor.pitch_deg == pytest.approx(truth.pitch_deg, abs=0.1)
    assert floor.roll_deg == pytest.approx(truth.roll_deg, abs=0.1)


def test_the_floor_survives_sensor_noise_and_holes(room: Path) -> None:
    """1% depth noise on every pixel and a tenth of the pixels without depth, as a
    Kinect-style sensor gives: the camera's height still within 2%."""
    truth = _truth(room).camera
    assert truth is not None and truth.height_m is not None and truth.pitch_deg is not None
    inputs = read_input_folder(room)
    assert inputs.depth is not None and inputs.K is not None
    rng = np.random.default_rng(5)
    depth = inputs.depth.metres * (1.0 + rng.normal(0.0, 0.01, inputs.depth.metres.shape))
    depth[rng.random(depth.shape) < 0.1] = 0.0
    camera = PinholeCamera(inputs.K, truth.pitch_deg + 3.0, (truth.roll_deg or 0.0) - 2.0)
    floor = fit_floor(point_grid(depth, inputs.K, 4), camera.world_from_cv.T @ [0.0, 1.0, 0.0])
    assert floor is not None
    assert floor.camera_height == pytest.approx(truth.height_m, rel=0.02)
    assert floor.pitch_deg == pytest.approx(truth.pitch_deg, abs=0.5)


def test_with_depth_scale_room_and_boxes_come_from_the_points(room: Path) -> None:
    truth = _truth(room)
    scene = _run(room, use_depth=True)
    assert {"layout_from_depth", "boxes_from_depth"} <= {s.name for s in scene.stages}
    assert "boxes_by_refiner" not in {s.name for s in scene.stages}  # learned without depth
    assert scene.camera is not None and truth.camera is not None
    assert scene.camera.height_m == pytest.approx(truth.camera.height_m, rel=0.02)
    assert scene.camera.height_source == "depth"
    assert scene.layout is not None and truth.layout is not None
    # The walls and ceiling the photo shows are planes of the depth: the front wall's distance
    # and the ceiling's height within a few centimetres.
    got, want = np.array(scene.layout.corners_3d), np.array(truth.layout.corners_3d)
    assert _front_distance(got) == pytest.approx(_front_distance(want), abs=0.05)
    assert np.abs(got[4:, 1] - want[4:, 1]).max() < 0.05
    true_corners = {o.id: o.corners_3d for o in truth.objects}
    ious = [
        iou_3d(np.array(o.corners_3d), np.array(true_corners[o.id]))
        for o in scene.objects
        if o.corners_3d is not None and true_corners.get(o.id) is not None
    ]
    assert len(ious) >= 5
    assert np.mean(np.array(ious) >= 0.15) >= 0.6


def test_without_depth_the_single_photo_path_is_unchanged(room: Path) -> None:
    single = tuple(s for s in DEFAULT_STAGES if s not in {"layout_from_depth", "boxes_from_depth"})
    without = _run(room, use_depth=False)
    before = _run(room, use_depth=False, stages=single)
    assert [s.name for s in without.stages] == [s.name for s in before.stages]
    assert not {"layout_from_depth", "boxes_from_depth"} & {s.name for s in without.stages}
    assert "boxes_by_refiner" in {s.name for s in without.stages}
    assert without.camera == before.camera
    assert without.camera is not None and without.camera.height_source == "estimated"
    assert without.layout == before.layout
    assert [o.box_3d for o in without.objects] == [o.box_3d for o in before.objects]
