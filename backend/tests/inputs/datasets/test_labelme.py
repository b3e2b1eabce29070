"""LabelMe files: polygons, circles and masks with masks, rectangles as boxes, the shapes of one
group as one object, the photo beside, in another folder or embedded, and bad files refused
one by one."""

from __future__ import annotations

import io
import json
from base64 import b64encode
from pathlib import Path

import numpy as np
import pytest
from holiscene.inputs.datasets import dataset_items
from holiscene.segmentation.rle import decode_mask
from PIL import Image

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
    labelme_file(tmp_path / "e_ellipse.json", [shape("lamp", [[5, 5], [9, 9]], "ellipse")])
    items = list(dataset_items(tmp_path))
    assert [Path(i.name).name for i in items] == [
        "a_good.json",
        "b_two_points.json",
        "c_broken.json",
        "d_missing.json",
        "e_ellipse.json",
    ]
    assert items[0].inputs is not None and items[0].error is None
    errors = [i.error or "" for i in items[1:]]
    assert "at least 3 points, it has 2" in errors[0]
    assert "not valid JSON" in errors[1]
    assert "d_missing.png is missing" in errors[2]
    assert "'ellipse' is not read" in errors[3]
    assert all(i.inputs is None for i in items[1:])


def test_shapes_of_one_group_are_one_object_as_labelme_reads_them(tmp_path: Path) -> None:
    """A sofa seen in two pieces (one group), a chair alone, a second chair of no group, a
    circle, a mask, LabelMe's reserved regions and a line (left out with a note)."""
    patch = io.BytesIO()
    Image.fromarray(np.full((4, 6), 255, np.uint8)).save(patch, "PNG")
    parts = [
        {**shape("sofa", [[5, 30], [20, 30], [20, 45]]), "group_id": 1},
        shape("chair", [[30, 5], [40, 5], [40, 15]]),
        {**shape("sofa", [[40, 30], [55, 30], [55, 45]]), "group_id": 1},
        shape("chair", [[60, 5], [70, 5], [70, 15]]),
        shape("lamp", [[80, 20], [84, 20]], "circle"),
        {
            **shape("pillow", [[10, 50], [15, 53]], "mask"),
            "mask": b64encode(patch.getvalue()).decode(),
        },
        shape("__ignore__", [[0, 0], [5, 0], [5, 5]]),
        shape("_background_", [[0, 0], [90, 0], [90, 60]]),
        shape("bed", [[1, 1], [9, 9]], "line"),
    ]
    (item,) = dataset_items(labelme_file(tmp_path / "room.json", parts))
    assert item.inputs is not None, item.error
    sofa, chair, second_chair, lamp, pillow = item.inputs.detections or []
    assert (sofa.cls, chair.cls, second_chair.cls, lamp.cls, pillow.cls) == (
        "sofa", "chair", "chair", "lamp", "pillow",
    )  # fmt: skip
    assert sofa.bbox == (5.0, 30.0, 56.0, 46.0)  # both pieces
    assert lamp.bbox == (76.0, 16.0, 85.0, 25.0)  # a disc of radius 4 about (80, 20)
    assert pillow.bbox == (10.0, 50.0, 16.0, 54.0) and pillow.mask is not None
    assert decode_mask(pillow.mask, WIDTH, HEIGHT).sum() == 24
    assert item.inputs.notes == ("shape 8 (bed): a line outlines no object; left out",)


def test_the_photo_is_found_as_labelme_users_write_its_path(tmp_path: Path) -> None:
    """A Windows path to a folder beside, and an imagePath that is no photo (the JSON itself,
    as LabelMe writes for a photo it embeds) with the photo in imageData."""
    windows = labelme_file(
        tmp_path / "images" / "room.json", [shape("bed", [[5, 5], [40, 5], [40, 40]])]
    )
    document = json.loads(windows.read_text())
    document["imagePath"] = "..\\images\\room.png"
    (tmp_path / "annotations").mkdir()
    (tmp_path / "annotations" / "room.json").write_text(json.dumps(document))
    embedded = labelme_file(tmp_path / "embedded.json", [], embed=True)
    document = json.loads(embedded.read_text())
    document["imagePath"] = "embedded.json"
    embedded.write_text(json.dumps(document))
    for path in (tmp_path / "annotations" / "room.json", embedded):
        (item,) = dataset_items(path)
        assert item.inputs is not None, item.error
        assert (item.inputs.photo.width, item.inputs.photo.height) == (WIDTH, HEIGHT)
    (item,) = dataset_items(embedded)
    assert item.inputs is not None and item.inputs.detections is None  # no shapes: detect


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
