"""Metric scale: the learned per-class calibration and the fusion of the priors."""

from __future__ import annotations

import math

import numpy as np
import pytest
from holiscene.geometry.camera import PinholeCamera
from holiscene.geometry.metric_scale import (
    CAMERA_HEIGHT_PRIOR,
    MIN_CALIBRATION_COUNT,
    SPREAD_WIDENING,
    ClassCalibration,
    ScaleCalibration,
    bottom_may_be_hidden,
    camera_height,
    default_calibration,
    fit_calibration,
)
from holiscene.knowledge.object_sizes import height_spread
from holiscene_schema import SceneObject


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
