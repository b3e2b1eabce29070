"""COCO instance files: polygons, both RLE forms, crowd regions, class names, and bad items
refused one by one."""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np
import pytest
from holiscene.export.coco import coco_rle
from holiscene.inputs.datasets import dataset_items
from holiscene.inputs.datasets.coco import decode_rle_string, encode_rle_string, rle_pixels
from holiscene.segmentation.rle import decode_mask

from .files import HEIGHT, WIDTH, coco_file, write_json


def _block(x0: int, y0: int, x1: int, y1: int) -> np.ndarray:
    mask = np.zeros((HEIGHT, WIDTH), dtype=bool)
    mask[y0:y1, x0:x1] = True
    return mask


def test_the_string_form_of_rle_counts_round_trips() -> None:
    assert encode_rle_string([5, 3]) == "53"
    assert decode_rle_string("53") == [5, 3]
    # From the fourth count on, the difference to the count two before is written (here -1).
    assert encode_rle_string([1, 2, 3, 1]) == "123O"
    rng = np.random.default_rng(1)
    counts = [int(c) for c in rng.integers(0, 5000, 200)]
    assert decode_rle_string(encode_rle_string(counts)) == counts


def test_polygons_and_both_rle_forms_become_given_masks(tmp_path: Path) -> None:
    block = _block(10, 20, 40, 50)
    rle = coco_rle(_block(50, 5, 90, 30))
    compressed = {**rle, "counts": encode_rle_string(rle["counts"])}
    path = coco_file(
        tmp_path,
        [
            {
                "id": 1,
                "image_id": 1,
                "category_id": 1,
                "bbox": [10, 20, 30, 30],
                "iscrowd": 0,
                # COCO's coordinates: pixel x spans [x, x + 1), so the block's outline
                # runs along its outer edges.
                "segmentation": [[10, 20, 40, 20, 40, 50, 10, 50]],
            },
            {
                "id": 2,
                "image_id": 1,
                "category_id": 2,
                "bbox": [50, 5, 40, 25],
                "segmentation": rle,
            },
            {
                "id": 3,
                "image_id": 1,
                "category_id": 3,
                "bbox": [50, 5, 40, 25],
                "segmentation": compressed,
            },
            {
                "id": 4,
                "image_id": 1,
                "category_id": 1,
                "bbox": [0, 0, 5, 5],
                "iscrowd": 1,
                "segmentation": coco_rle(_block(0, 0, 5, 5)),
            },
        ],
    )
    (item,) = dataset_items(path)
    assert item.error is None and item.inputs is not None
    detections = item.inputs.detections or []
    assert [d.cls for d in detections] == ["sofa", "otherprop", "otherprop"]  # crowd left out
    assert [d.source_class for d in detections] == ["couch", "basket", "teapot"]
    assert detections[0].bbox == (10.0, 20.0, 40.0, 50.0)
    masks = [decode_mask(d.mask, WIDTH, HEIGHT) for d in detections if d.mask is not None]
    assert len(masks) == 3 and all(d.mask and d.mask.source == "given" for d in detections)
    assert np.array_equal(masks[0], block)
    assert np.array_equal(masks[1], _block(50, 5, 90, 30))
    assert np.array_equal(masks[2], masks[1])


def test_a_class_map_beside_the_file_names_the_classes(tmp_path: Path) -> None:
    path = coco_file(tmp_path, [{"id": 1, "image_id": 1, "category_id": 3, "bbox": [1, 1, 9, 9]}])
    (tmp_path / "class_map.json").write_text(json.dumps({"teapot": "shelves"}))
    (item,) = dataset_items(path)
    assert item.inputs is not None and item.inputs.detections is not None
    assert item.inputs.detections[0].cls == "shelves"
    assert item.inputs.detections[0].mask is None


@pytest.mark.parametrize(
    ("annotation", "message"),
    [
        ({"segmentation": [[1, 1, 20, 20]]}, "at least 3 points, it has 2"),
        ({"segmentation": {"counts": [3, 4], "size": [HEIGHT, WIDTH]}}, "add up to 7"),
        ({"segmentation": {"counts": [3], "size": [10, 10]}}, "not the image's"),
        ({"segmentation": {"counts": "5\x7f", "size": [HEIGHT, WIDTH]}}, "stray character"),
        ({"category_id": 9}, "category 9 is not listed"),
        ({"bbox": [80, 50, 40, 40]}, "outside the 96x64 image"),
    ],
)
def test_a_bad_annotation_refuses_its_image_only(
    tmp_path: Path, annotation: dict[str, object], message: str
) -> None:
    good = {"id": 1, "image_id": 2, "category_id": 1, "bbox": [1, 1, 20, 20]}
    bad = {"id": 2, "image_id": 1, "category_id": 1, "bbox": [1, 1, 20, 20], **annotation}
    path = coco_file(tmp_path, [good, bad], images=("a.png", "b.png"))
    first, second = dataset_items(path)
    assert first.name == "a.png" and first.inputs is None
    assert first.error is not None and message in first.error, first.error
    assert second.error is None and second.inputs is not None


def test_a_missing_image_refuses_that_image_only(tmp_path: Path) -> None:
    path = coco_file(tmp_path, [], images=("a.png", "gone.png"), written=("a.png",))
    first, second = dataset_items(tmp_path)  # the folder holding annotations.json
    assert first.inputs is not None and first.inputs.detections == []
    assert second.name == "gone.png" and second.error is not None
    assert "gone.png is missing" in second.error
    assert path.is_file()


def test_a_file_that_is_not_json_is_one_error(tmp_path: Path) -> None:
    path = tmp_path / "instances_val.json"
    path.write_text('{"images": [')
    (item,) = dataset_items(path)
    assert item.error is not None and "not valid JSON" in item.error
    other = write_json(tmp_path / "other.json", {"hello": 1})
    (item,) = dataset_items(other)
    assert item.error is not None and "neither a COCO" in item.error


def test_rle_counts_must_be_whole_numbers() -> None:
    with pytest.raises(ValueError, match="whole numbers"):
        rle_pixels([1.5, 2], 1, 3)


def _box(number: int, **extra: object) -> dict[str, object]:
    x = 2 + 20 * number
    return {"id": number + 1, "image_id": 1, "category_id": 1, "bbox": [x, 2, 15, 15], **extra}


def test_holiscene_support_becomes_people_labels_over_the_boxes(tmp_path: Path) -> None:
    annotations = [
        _box(0, holiscene_id="table", holiscene_support={"parent": "floor", "type": "below"}),
        _box(1, iscrowd=1, holiscene_id="crowd"),  # left out: the boxes after it move up
        _box(2, holiscene_id="cup", holiscene_support={"parent": "table", "type": "below"}),
        _box(3, holiscene_id="frame", holiscene_support={"parent": "wall", "type": "behind"}),
        _box(4, holiscene_id="loose"),
    ]
    (item,) = dataset_items(coco_file(tmp_path, annotations))
    assert item.inputs is not None and item.inputs.detections is not None
    assert len(item.inputs.detections) == 4
    assert [(s.child, s.parent, s.type, s.source) for s in item.inputs.supports] == [
        ("o0", "floor", "below", "manual"),
        ("o1", "o0", "below", "manual"),
        ("o2", "wall", "behind", "manual"),
    ]


@pytest.mark.parametrize(
    ("support", "message"),
    [
        ({"parent": "nobody", "type": "below"}, "parent 'nobody' is neither floor"),
        ({"parent": "a"}, "must be an object with 'parent' and 'type'"),
        ({"parent": "a", "type": "on"}, "type 'on' is neither"),
        ({"parent": "b", "type": "below"}, "support cycle"),
    ],
)
def test_a_bad_holiscene_support_refuses_its_image(
    tmp_path: Path, support: dict[str, object], message: str
) -> None:
    annotations = [
        _box(0, holiscene_id="a", holiscene_support=support),
        _box(1, holiscene_id="b", holiscene_support={"parent": "a", "type": "below"}),
    ]
    (item,) = dataset_items(coco_file(tmp_path, annotations))
    assert item.inputs is None and item.error is not None
    assert "holiscene_support" in item.error and message in item.error, item.error


def test_a_small_polygon_covers_the_pixels_whose_centres_it_holds_as_cocos_tools_do() -> None:
    from holiscene.inputs.datasets.items import polygon_pixels

    triangle = [0, 0, 10, 0, 0, 10]  # area 50
    coco = polygon_pixels("t", triangle, 20, 20, at_pixel_centres=True)
    assert coco.sum() == 45  # the pixels (i, j) with i + j + 1 < 10
    assert coco[0, 8] and not coco[0, 9] and not coco[5, 5]
    labelme = polygon_pixels("t", triangle, 20, 20)  # LabelMe's own fill takes the edge too
    assert labelme.sum() > 60 and (labelme | coco).sum() == labelme.sum()


@pytest.mark.parametrize("entry_size", ["upright", "as stored"])
def test_a_photo_with_an_exif_quarter_turn_follows_the_size_its_entry_gives(
    tmp_path: Path, entry_size: str
) -> None:
    """A phone photo stored 64 wide and 96 high with a quarter turn shows 96x64. Most tools label
    what they show; an entry with the stored size was labelled without the turn."""
    from PIL import ExifTags, Image

    upright = np.zeros((HEIGHT, WIDTH, 3), dtype=np.uint8)
    upright[:10, :20] = 255  # a white block at the upright photo's top left
    stored = Image.fromarray(upright).transpose(Image.Transpose.ROTATE_90)
    exif = Image.Exif()
    exif[ExifTags.Base.Orientation] = 6
    path = coco_file(tmp_path, [{"id": 1, "image_id": 1, "category_id": 1, "bbox": [0, 0, 20, 10]}])
    stored.save(tmp_path / "images" / "a.png", exif=exif.tobytes())
    if entry_size == "as stored":
        data = json.loads(path.read_text())
        data["images"][0].update(width=HEIGHT, height=WIDTH)
        write_json(path, data)
    (item,) = dataset_items(path)
    assert item.error is None and item.inputs is not None
    rgb = item.inputs.photo.rgb
    if entry_size == "upright":
        assert rgb.shape == (HEIGHT, WIDTH, 3) and rgb[:10, :20].min() == 255
        assert item.inputs.notes == ()
    else:
        assert rgb.shape == (WIDTH, HEIGHT, 3)
        np.testing.assert_array_equal(rgb, np.asarray(stored))
        assert any("EXIF turn was left out" in note for note in item.inputs.notes)
