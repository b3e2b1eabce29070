"""Depth given with a photo: a 16-bit PNG of millimetres (SUN RGB-D's with its bits rotated)
or metres; refused with a clear message when it cannot be depth for this photo; kept beside
the stored scene and referenced from it."""

from __future__ import annotations

import shutil
from pathlib import Path

import cv2
import numpy as np
import pytest
from holiscene.core.settings import Settings
from holiscene.inputs import InputError, depth_from_metres, depth_from_png, read_input_folder
from holiscene.services.workbench import Workbench, imported_scene


def _png(array: np.ndarray) -> bytes:
    ok, data = cv2.imencode(".png", array)
    assert ok
    return bytes(data.tobytes())


def test_millimetres_read_as_metres_and_zero_stays_no_depth() -> None:
    mm = np.full((40, 60), 2500, np.uint16)
    mm[:5] = 0
    depth = depth_from_png(_png(mm), 60, 40)
    assert depth.metres.dtype == np.float32
    assert depth.metres[10, 10] == pytest.approx(2.5)
    assert (depth.metres[:5] == 0).all()
    again = cv2.imdecode(np.frombuffer(depth.png, np.uint8), cv2.IMREAD_UNCHANGED)
    assert (again == mm).all()


def test_sun_rgbd_bit_rotation_is_undone() -> None:
    mm = np.full((40, 60), 1234, np.uint16)
    stored = np.bitwise_or(np.left_shift(mm, 3), np.right_shift(mm, 13))
    depth = depth_from_png(_png(stored), 60, 40, sunrgbd_bit_rotation=True)
    assert depth.metres[0, 0] == pytest.approx(1.234)
    plain = depth_from_png(_png(stored), 60, 40)
    assert plain.metres[0, 0] != pytest.approx(1.234)


@pytest.mark.parametrize(
    ("array", "message"),
    [
        (np.full((40, 61), 1000, np.uint16), "61x40 pixels, the photo is 60x40"),
        (np.zeros((40, 60), np.uint16), "holds no depth"),
        (np.full((40, 60), 100, np.uint8), "8-bit image"),
        (np.full((40, 60, 3), 1000, np.uint16), "channels"),
    ],
)
def test_what_cannot_be_depth_is_refused(array: np.ndarray, message: str) -> None:
    with pytest.raises(InputError, match=message):
        depth_from_png(_png(array), 60, 40)


def test_metres_with_nan_are_no_depth_there_and_all_nan_is_refused() -> None:
    metres = np.full((40, 60), 3.0, np.float32)
    metres[0] = np.nan
    metres[1] = -1.0
    depth = depth_from_metres(metres, 60, 40, "depths")
    assert (depth.metres[:2] == 0).all() and depth.metres[5, 5] == pytest.approx(3.0)
    with pytest.raises(InputError, match="holds no depth"):
        depth_from_metres(np.full((40, 60), np.nan, np.float32), 60, 40, "depths")
    with pytest.raises(InputError, match="not a PNG"):
        depth_from_png(b"not a png", 60, 40)


def test_an_input_folder_with_depth_is_stored_with_it(
    synthetic_folder: Path, settings: Settings, tmp_path: Path
) -> None:
    with_depth = read_input_folder(synthetic_folder)
    without = read_input_folder(synthetic_folder, use_depth=False)
    assert with_depth.depth is not None and without.depth is None
    assert with_depth.digest != without.digest
    true_mm = cv2.imread(str(synthetic_folder / "depth.png"), cv2.IMREAD_UNCHANGED)
    assert np.allclose(with_depth.depth.metres, true_mm * 0.001)

    workbench = Workbench(settings)
    try:
        summary = workbench.scenes.create(with_depth, imported_scene(with_depth, "room"), "import")
        scene = workbench.scenes.document(summary.id).scene
        assert scene.depth is not None and scene.depth.file == "depth.png"
        stored = workbench.scenes.files.folder(summary.id) / scene.depth.file
        assert (cv2.imread(str(stored), cv2.IMREAD_UNCHANGED) == true_mm).all()
    finally:
        workbench.close()

    broken = tmp_path / "broken"
    shutil.copytree(synthetic_folder, broken)
    cv2.imwrite(str(broken / "depth.png"), np.zeros((10, 10), np.uint16))
    with pytest.raises(InputError, match=r"depth\.png is 10x10 pixels"):
        read_input_folder(broken)
