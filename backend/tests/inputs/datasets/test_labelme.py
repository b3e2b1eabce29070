"""LabelMe files: polygons with masks, rectangles as boxes, the photo beside or embedded, and
bad files refused one by one."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest
from holiscene.inputs.datasets import dataset_items
from holiscene.segmentation.rle import decode_mask

from .files import HEIGHT, WIDTH, labelme_file, shape


@pytest.mark.parametrize("embed", [False, True])
def test_polygons_and_rectangles_are_read(tmp_path: Path, embed: bool) -> None:
    path = labelme_file(
        tmp_path / "room.json",
        [
            shape("chair", [[10, 10], [30, 10], [30, 40], [10, 40]]),
            shape("night-stand", [[50, 20], [80, 50]], "rectangle"),
        ],
        embed=embed,
    )
    (item,) = dataset_items(path)
    assert item.error is None and item.inputs is not None
    chair, stand = item.inputs.detections or []
    assert (chair.cls, stand.cls) == ("chair", "night_stand")
    assert chair.bbox == (10.0, 10.0, 31.0, 41.0)  # the outline's pixels, edges included
    assert chair.mask is not None
    pixels = decode_mask(chair.mask, WIDTH, HEIGHT)
    assert pixels.sum() == 21 * 31 and pixels[10:41, 10:31].all()
    assert stand.bbox == (50.0, 20.0, 80.0, 50.0) and stand.mask is None
    assert item.inputs.photo.width == WIDTH and item.inputs.photo.height == HEIGHT


def test_a_bad_file_is_its_own_error_and_the_rest_are_read(tmp_path: Path) -> None:
    labelme_file(tmp_path / "a_good.json", [shape("bed", [[5, 5], [40, 5], [40, 40]])])
    labelme_file(tmp_path / "b_two_points.json", [shape("bed", [[5, 5], [40, 5]])])
    (tmp_path / "c_broken.json").write_text("{not json")
    missing = labelme_file(tmp_path / "d_missing.json", [])
    missing.with_suffix(".png").unlink()
    labelme_file(tmp_path / "e_circle.json", [shape("lamp", [[5, 5], [9, 9]], "circle")])
    items = list(dataset_items(tmp_path))
    assert [Path(i.name).name for i in items] == [
        "a_good.json",
        "b_two_points.json",
        "c_broken.json",
        "d_missing.json",
        "e_circle.json",
    ]
    assert items[0].inputs is not None and items[0].error is None
    errors = [i.error or "" for i in items[1:]]
    assert "at least 3 points, it has 2" in errors[0]
    assert "not valid JSON" in errors[1]
    assert "d_missing.png is missing" in errors[2]
    assert "'circle' is not read" in errors[3]
    assert all(i.inputs is None for i in items[1:])


def test_the_mask_follows_a_slanted_polygon(tmp_path: Path) -> None:
    path = labelme_file(tmp_path / "tri.json", [shape("lamp", [[10, 10], [60, 10], [10, 60]])])
    (item,) = dataset_items(path)
    assert item.inputs is not None
    (lamp,) = item.inputs.detections or []
    assert lamp.mask is not None
    pixels = decode_mask(lamp.mask, WIDTH, HEIGHT)
    assert pixels[12, 12] and not pixels[50, 50]
    assert abs(int(pixels.sum()) - 51 * 51 // 2) < 80
    assert np.isclose(lamp.bbox[0], 10.0)


def test_paths_that_are_no_dataset(tmp_path: Path) -> None:
    from holiscene.inputs.datasets import is_dataset

    (item,) = dataset_items(tmp_path / "nowhere.json")
    assert item.error is not None and "cannot be read" in item.error
    assert is_dataset(tmp_path / "nowhere.json")
    folder = tmp_path / "input"
    folder.mkdir()
    (folder / "detections.json").write_text("[]")
    assert not is_dataset(folder)  # an input folder missing its photo: refused as one
    (folder / "img.png").write_bytes(b"")
    (folder / "extra.json").write_text("{}")
    assert not is_dataset(folder)
