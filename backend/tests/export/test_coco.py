"""COCO instances export: category ids, bbox convention, and masks that survive the round trip
through COCO's uncompressed RLE."""

from __future__ import annotations

from functools import cache

import numpy as np
from holiscene.export.coco import coco_instances, coco_rle, decode_coco_rle
from holiscene.segmentation.rle import decode_mask
from holiscene.synth.generate import SyntheticScene, synthesize
from holiscene_schema import NYU40_CLASSES, Scene


@cache
def synthetic(seed: int) -> SyntheticScene:
    return synthesize(seed)


def test_rle_runs_go_down_the_columns_and_start_with_background() -> None:
    mask = np.array([[0, 1], [1, 1], [0, 0]], dtype=bool)  # 3 rows, 2 columns
    # Column-major: 0 1 0 | 1 1 0 -> runs 1 (bg), 1, 1 (bg), 2, 1 (bg).
    assert coco_rle(mask) == {"counts": [1, 1, 1, 2, 1], "size": [3, 2]}
    starts_on = np.array([[1, 0], [0, 0]], dtype=bool)
    assert coco_rle(starts_on)["counts"] == [0, 1, 3]


def test_every_mask_comes_back_from_coco_pixel_for_pixel() -> None:
    scene = synthetic(2001).truth
    assert sum(o.mask is not None for o in scene.objects) >= 3
    coco = coco_instances(scene)
    width, height = scene.image.width, scene.image.height
    assert coco["images"] == [
        {"id": 1, "file_name": scene.image.file, "width": width, "height": height}
    ]
    by_id = {a["holiscene_id"]: a for a in coco["annotations"]}
    assert len(by_id) == len(scene.objects)
    for obj in scene.objects:
        annotation = by_id[obj.id]
        assert obj.mask is not None
        ours = decode_mask(obj.mask, width, height)
        theirs = decode_coco_rle(annotation["segmentation"])
        assert np.array_equal(ours, theirs), obj.id
        assert sum(annotation["segmentation"]["counts"]) == width * height
        assert annotation["area"] == int(ours.sum())
        x1, y1, x2, y2 = obj.bbox
        assert annotation["bbox"] == [x1, y1, x2 - x1, y2 - y1]
        assert annotation["iscrowd"] == 0 and annotation["image_id"] == 1


def test_categories_are_the_nyu40_labels_with_stable_ids() -> None:
    scene = synthetic(2001).truth
    categories = coco_instances(scene)["categories"]
    assert [c["name"] for c in categories] == list(NYU40_CLASSES)
    assert [c["id"] for c in categories] == list(range(1, 41))
    ids = {c["name"]: c["id"] for c in categories}
    assert ids["chair"] == 5 and ids["otherprop"] == 40
    for annotation, obj in zip(coco_instances(scene)["annotations"], scene.objects, strict=True):
        assert annotation["category_id"] == ids[obj.cls]


def test_an_object_without_a_mask_is_its_box_as_a_polygon() -> None:
    truth = synthetic(2001).truth
    obj = truth.objects[0].model_copy(update={"mask": None, "bbox": [10.0, 20.0, 50.0, 80.0]})
    scene = Scene.model_validate(truth.model_copy(update={"objects": [obj], "supports": []}))
    (annotation,) = coco_instances(scene)["annotations"]
    assert annotation["segmentation"] == [[10.0, 20.0, 50.0, 20.0, 50.0, 80.0, 10.0, 80.0]]
    assert annotation["area"] == 40.0 * 60.0
