"""Metric scale: the learned per-class calibration and the fusion of the priors."""

from __future__ import annotations

import math

import numpy as np
import pytest
from holiscene.geometry.camera import PinholeCamera
from holiscene.geometry.metric_scale import (
    CAMERA_HEIGHT_PRIOR,
    FRONT_WALL_PRIOR,
    LOWEST_CAMERA_M,
    MIN_CALIBRATION_COUNT,
    PRIOR_GATE,
    SPREAD_WIDENING,
    TOO_LARGE_FACTOR,
    ClassCalibration,
    ScaleCalibration,
    bottom_may_be_hidden,
    camera_height,
    default_calibration,
    fit_calibration,
    mounting_points,
    too_large_to_stand_there,
)
from holiscene.geometry.room_layout import RoomHypothesis
from holiscene.knowledge.object_sizes import height_spread, mounting_height
from holiscene.shapes.library import SIZE_RANGES
from holiscene_schema import SceneObject
from holiscene_schema.support_geometry import TOO_LARGE_LIMITS


def test_fit_takes_the_median_and_a_robust_spread() -> None:
    rng = np.random.default_rng(0)
    values = rng.normal(0.2, 0.1, 400)
    values[:20] = 3.0  # a few boxes measured across occluders
    residuals = [("height", "chair", float(v)) for v in values] + [("width", "chair", 0.5)] * 9
    calibration = fit_calibration(residuals, "test")
    assert calibration.kinds["width"]["chair"] == ClassCalibration(0.5, 0.0, 9)
    chair = calibration.kinds["height"]["chair"]
    assert chair.count == 400
    assert chair.bias == pytest.approx(0.2, abs=0.02)
    assert chair.sd == pytest.approx(0.1, abs=0.02)


def test_rare_classes_fall_back_to_the_library_spread_or_are_not_used() -> None:
    classes = {"door": ClassCalibration(0.05, 0.06, 100), "bed": ClassCalibration(0.4, 0.01, 2)}
    calibration = ScaleCalibration({"height": classes, "width": classes})
    assert calibration.measurement_error("height", "door") == (0.05, 0.06)
    assert calibration.measurement_error("width", "door") == (0.05, 0.06)
    error = calibration.measurement_error("height", "bed")  # too few to trust
    assert error is not None and error[0] == 0.0 and error[1] > height_spread("bed")
    assert calibration.measurement_error("width", "bed") is None  # raw widths are not used
    assert calibration.measurement_error("mounting", "door") is None  # nor raw mountings
    assert MIN_CALIBRATION_COUNT > 2


def test_calibration_round_trips_through_json() -> None:
    desk = {"desk": ClassCalibration(-0.0123, 0.15, 44)}
    calibration = ScaleCalibration({"height": desk, "width": desk}, "here")
    again = ScaleCalibration.from_json(calibration.to_json())
    assert again == calibration


def test_the_shipped_calibration_covers_the_common_floor_classes() -> None:
    calibration = default_calibration()
    for kind in ("height", "width"):
        for cls in ("chair", "table", "door", "sofa"):
            assert calibration.kinds[kind][cls].count >= MIN_CALIBRATION_COUNT
            assert abs(calibration.kinds[kind][cls].bias) < 0.5
    for cls in ("picture", "window"):
        assert calibration.kinds["mounting"][cls].count >= MIN_CALIBRATION_COUNT
        assert calibration.kinds["mounting"][cls].sd < CAMERA_HEIGHT_PRIOR[1] * 2


def test_without_evidence_the_camera_prior_decides() -> None:
    camera = PinholeCamera(np.array([[500.0, 0, 320], [0, 500, 240], [0, 0, 1]]), 10.0, 0.0)
    alone = camera_height(camera, [], None, 640)
    assert alone.metres == pytest.approx(CAMERA_HEIGHT_PRIOR[0])
    assert alone.priors == "camera height"
    assert alone.spread == pytest.approx(SPREAD_WIDENING * CAMERA_HEIGHT_PRIOR[1])
    assert alone.describe() == "camera height, about ±14%"
    # A seen ceiling 1.2 camera heights up pulls towards 2.75 m / 2.2 = 1.25 m, and the two
    # priors together leave less doubt than either.
    both = camera_height(camera, [], 1.2, 640)
    assert 1.25 < both.metres < CAMERA_HEIGHT_PRIOR[0] and "room height" in both.priors
    assert math.isfinite(both.metres)
    assert both.spread < alone.spread


def test_a_bottom_edge_behind_a_nearer_object_may_be_hidden() -> None:
    """A box cut off by a nearer object ends where the view does, not on the floor: its
    contact would lie too far away (and push the room's walls out)."""
    chair = SceneObject(id="chair", cls="chair", bbox=[200.0, 150.0, 260.0, 300.0])
    table = SceneObject(id="table", cls="table", bbox=[150.0, 250.0, 400.0, 380.0])
    picture = SceneObject(id="picture", cls="picture", bbox=[150.0, 20.0, 300.0, 120.0])
    objects = [chair, table, picture]
    assert bottom_may_be_hidden(chair, objects)
    assert not bottom_may_be_hidden(table, objects)
    assert not bottom_may_be_hidden(picture, objects)  # nothing reaches over its bottom edge
    # Beside the table the chair's bottom edge is seen.
    chair_beside = chair.model_copy(update={"bbox": [420.0, 150.0, 480.0, 300.0]})
    assert not bottom_may_be_hidden(chair_beside, [chair_beside, table])


def test_wall_objects_offer_the_ends_of_their_telling_edge() -> None:
    picture = SceneObject(id="picture", cls="picture", bbox=[100.0, 40.0, 220.0, 130.0])
    window = SceneObject(id="window", cls="window", bbox=[400.0, 0.0, 480.0, 200.0])
    # A television standing on a dresser: its lower edge is on the dresser's box.
    dresser = SceneObject(id="dresser", cls="dresser", bbox=[240.0, 200.0, 380.0, 330.0])
    television = SceneObject(id="tv", cls="television", bbox=[260.0, 120.0, 360.0, 202.0])
    cut_off = SceneObject(id="mirror", cls="mirror", bbox=[10.0, 300.0, 90.0, 479.0])
    chair = SceneObject(id="chair", cls="chair", bbox=[500.0, 250.0, 560.0, 380.0])
    door = SceneObject(id="door", cls="door", bbox=[560.0, 30.0, 620.0, 300.0])
    objects = [picture, window, dresser, television, cut_off, chair, door]
    points = {obj.id: ends for obj, ends in mounting_points(objects, 480)}
    assert set(points) == {"picture", "window"}  # a window cut off at the top still counts
    assert points["picture"].tolist() == [[100.0, 130.0], [220.0, 130.0]]  # lower corners
    assert mounting_height("chair") is None and mounting_height("door") is None
    assert mounting_height("window") == pytest.approx(0.85)


def test_a_calibrated_wall_object_joins_the_scale() -> None:
    camera = PinholeCamera(np.array([[500.0, 0, 320], [0, 500, 240], [0, 0, 1]]), 10.0, 0.0)
    picture = SceneObject(id="picture", cls="picture", bbox=[100.0, 40.0, 220.0, 130.0])
    typical = mounting_height("picture")
    assert typical is not None
    # Its lower edge seen 0.8 camera heights above the floor says the camera is typical / 0.8
    # metres high; a sure calibration lets it outweigh the camera prior.
    sure = ScaleCalibration({"mounting": {"picture": ClassCalibration(0.0, 0.02, 50)}})
    scale = camera_height(camera, [], None, 640, sure, mounted=[(picture, 0.8)])
    assert scale.metres == pytest.approx(typical / 0.8, rel=0.05)
    assert scale.priors == "camera height + 1 wall object(s)"
    # Uncalibrated, it is not used.
    alone = camera_height(camera, [], None, 640, ScaleCalibration(), mounted=[(picture, 0.8)])
    assert alone.metres == pytest.approx(CAMERA_HEIGHT_PRIOR[0])


def test_a_lone_measurement_far_from_the_camera_prior_is_dropped() -> None:
    """One object alone cannot be outvoted by the others' median: a picture whose lower edge
    reads a fifth of a camera height above the floor would put the camera several metres up."""
    camera = PinholeCamera(np.array([[500.0, 0, 320], [0, 500, 240], [0, 0, 1]]), 10.0, 0.0)
    picture = SceneObject(id="picture", cls="picture", bbox=[100.0, 40.0, 220.0, 130.0])
    typical = mounting_height("picture")
    assert typical is not None
    sd = 0.15
    sure = ScaleCalibration({"mounting": {"picture": ClassCalibration(0.0, sd, 50)}})
    gate = PRIOR_GATE * math.hypot(sd, CAMERA_HEIGHT_PRIOR[1])
    just_inside = typical / (CAMERA_HEIGHT_PRIOR[0] * math.exp(gate - 0.01))
    kept = camera_height(camera, [], None, 640, sure, mounted=[(picture, just_inside)])
    assert kept.metres > CAMERA_HEIGHT_PRIOR[0] * 1.3
    assert kept.priors == "camera height + 1 wall object(s)"
    beyond = typical / (CAMERA_HEIGHT_PRIOR[0] * math.exp(gate + 0.01))
    dropped = camera_height(camera, [], None, 640, sure, mounted=[(picture, beyond)])
    assert dropped.metres == pytest.approx(CAMERA_HEIGHT_PRIOR[0])
    assert dropped.priors == "camera height"


def test_rays_meet_the_walls_at_their_heights() -> None:
    room = RoomHypothesis(front=3.0, left=1.0, right=2.0, back=0.5, ceiling=1.0, score=0.0,
                          ceiling_seen=True)  # fmt: skip
    rays = np.array([
        [1.0, -0.1, 0.0],  # meets the front wall 0.3 below the camera
        [0.0, 0.2, 1.0],  # the right wall, 0.4 above
        [0.0, -0.5, -1.0],  # the left wall, 0.5 below
        [1.0, -1.0, 0.0],  # the floor first
        [1.0, 0.5, 0.0],  # the ceiling first
    ])  # fmt: skip
    heights = room.height_on_walls(rays)
    assert heights[:3] == pytest.approx([0.7, 1.4, 0.5])
    assert np.isnan(heights[3:]).all()


def test_a_seen_front_wall_pulls_towards_the_typical_room_depth() -> None:
    camera = PinholeCamera(np.array([[500.0, 0, 320], [0, 500, 240], [0, 0, 1]]), 10.0, 0.0)
    alone = camera_height(camera, [], None, 640)
    # A front wall 4 camera heights away says 4.67 m / 4 = 1.17 m; 3 says 1.56 m.
    near = camera_height(camera, [], None, 640, front_wall=4.0)
    far = camera_height(camera, [], None, 640, front_wall=3.0)
    assert FRONT_WALL_PRIOR[0] / 4.0 < near.metres < alone.metres < far.metres
    assert near.priors == "camera height + front wall distance"
    assert near.spread < alone.spread


DOWN_20 = PinholeCamera(np.array([[500.0, 0, 320], [0, 500.0, 240], [0, 0, 1]]), 20.0, 0.0)


def test_a_shelf_whose_bottom_edge_meets_the_floor_far_away_is_too_large_to_stand_there() -> None:
    # Bottom edge 52 px below the horizon (y = 58): the floor there is 10 camera heights away,
    # where 160 px span 3 m of floor even with a camera 0.87 m high.
    high_shelf = [400.0, 0.0, 560.0, 110.0]
    assert too_large_to_stand_there(DOWN_20, "shelves", high_shelf)
    # The same box lower in the photo stands nearer, at a believable size.
    assert not too_large_to_stand_there(DOWN_20, "shelves", [400.0, 0.0, 560.0, 150.0])
    assert not too_large_to_stand_there(DOWN_20, "bookshelf", [300.0, 60.0, 440.0, 256.0])
    # A catch-all class may be any size; a bottom edge above the horizon meets no floor.
    assert not too_large_to_stand_there(DOWN_20, "otherprop", high_shelf)
    assert not too_large_to_stand_there(DOWN_20, "shelves", [400.0, 0.0, 560.0, 40.0])


def test_the_shared_size_limits_are_the_furniture_librarys_sizes() -> None:
    """The contract's table (which the browser reads too) is 1.5 times each class's largest
    footprint diagonal and height over the lowest believable camera: change the library's
    sizes, and the table changes with them. NYU-40's catch-all classes may be of any size (a
    whiteboard, a coffee table, a piano) and have no limit."""
    factor = TOO_LARGE_FACTOR / LOWEST_CAMERA_M
    any_size = {"otherprop", "otherfurniture", "otherstructure"}
    expected = {
        cls: (
            round(math.hypot(ranges.depth[1], ranges.width[1]) * factor, 3),
            round(ranges.height[1] * factor, 3),
        )
        for cls, ranges in SIZE_RANGES.items()
        if cls not in any_size
    }
    assert expected == TOO_LARGE_LIMITS
