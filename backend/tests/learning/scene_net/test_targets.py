"""The layout and object networks' targets: a true room and its boxes survive the trip to the
targets and back, and bins give back the values they encode."""

from __future__ import annotations

import numpy as np
import pytest
from holiscene.geometry.boxes import corners_of
from holiscene.geometry.camera import PinholeCamera
from holiscene.learning.scene_net.bins import LOG_DISTANCE_BINS, OBJECT_YAW_BINS, PITCH_BINS, Bins
from holiscene.learning.scene_net.targets import ObjectTargets, RoomTargets, wrap_degrees
from holiscene.synth.generate import synthesize
from holiscene_schema import Scene


@pytest.fixture(scope="module")
def room() -> Scene:
    return synthesize(900_002).truth


def test_a_true_room_comes_back_from_its_targets(room: Scene) -> None:
    assert room.layout is not None and room.camera is not None
    corners = np.asarray(room.layout.corners_3d)
    targets = RoomTargets.of_truth(
        room.camera.pitch_deg or 0.0, room.camera.roll_deg or 0.0, corners
    )
    assert -45.0 <= targets.yaw_deg < 45.0
    assert targets.camera_height_m == pytest.approx(room.camera.height_m, abs=1e-3)
    assert (targets.distances > 0).all()
    # The same 8 corners in the same order (the room's yaw is taken modulo a quarter turn).
    assert np.abs(targets.corners_world() - corners).max() < 1e-3


def test_true_boxes_come_back_from_their_targets(room: Scene) -> None:
    assert room.camera is not None
    camera = PinholeCamera(
        np.asarray(room.camera.K), room.camera.pitch_deg or 0.0, room.camera.roll_deg or 0.0
    )
    checked = 0
    for obj in room.objects:
        if obj.box_3d is None:
            continue
        targets = ObjectTargets.of_truth(obj.box_3d, tuple(obj.bbox), obj.cls, camera)
        assert targets is not None
        box = targets.box(tuple(obj.bbox), obj.cls, camera)
        assert np.abs(corners_of(box) - corners_of(obj.box_3d)).max() < 2e-3
        checked += 1
    assert checked >= 3


def test_a_box_behind_the_camera_has_no_targets(room: Scene) -> None:
    assert room.camera is not None
    camera = PinholeCamera(np.asarray(room.camera.K), 0.0, 0.0)
    obj = next(o for o in room.objects if o.box_3d is not None)
    assert obj.box_3d is not None
    behind = obj.box_3d.model_copy(update={"center": [-2.0, 0.0, 0.0]})
    assert ObjectTargets.of_truth(behind, tuple(obj.bbox), obj.cls, camera) is None


@pytest.mark.parametrize("bins", [PITCH_BINS, LOG_DISTANCE_BINS, OBJECT_YAW_BINS, Bins(0, 1, 3)])
def test_bins_decode_what_they_encode(bins: Bins) -> None:
    values = np.linspace(bins.low + 1e-6, bins.high - 1e-6, 17)
    index, offsets = bins.encode(values)
    assert (np.abs(offsets) <= 0.5 + 1e-9).all()
    logits = np.eye(bins.count)[index]
    repeated = np.repeat(offsets[:, None], bins.count, axis=1)
    assert np.allclose(bins.decode(logits, repeated), values)
    # Beyond the range: the end bin, with an offset that reaches the value.
    index, offsets = bins.encode(np.array([bins.high + bins.width]))
    assert index[0] == bins.count - 1 and offsets[0] == pytest.approx(1.5)


def test_angles_wrap_into_half_open_ranges() -> None:
    assert float(wrap_degrees(190.0)) == pytest.approx(-170.0)
    assert float(wrap_degrees(-180.0)) == pytest.approx(-180.0)
    assert float(wrap_degrees(50.0, 90.0)) == pytest.approx(-40.0)
