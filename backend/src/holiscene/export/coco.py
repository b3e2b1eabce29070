"""A scene's objects as a COCO instances file (one image), for detection and segmentation
tools that read COCO.

- categories: the 40 NYU-40 classes, id = NYU-40 label (index + 1), the same in every file;
- annotations: bbox as COCO [x, y, width, height]; segmentation as COCO's uncompressed RLE
  (`counts` over the image in column-major order, starting with background) from the
  object's mask, or the box as a polygon when it has none; area in pixels of that shape;
  `holiscene_id` keeps the object's id.

coco_dataset writes several scenes as one file (an image each), every annotation with its
object's support as `holiscene_support` {parent, type} (the parent an object's
`holiscene_id`, or floor/wall/ceiling) with who set it: `author` for a person's label, or
`source` "auto" and `confidence` for the pipeline's guess, so a guess imports as a guess.
"""

from __future__ import annotations

from collections.abc import Sequence
from typing import Any

import numpy as np
from holiscene_schema import NYU40_CLASSES, STRUCTURAL_CLASSES, Scene, SceneObject

from ..segmentation.rle import decode_mask
from .input_folder import support_provenance

CATEGORY_IDS: dict[str, int] = {name: index + 1 for index, name in enumerate(NYU40_CLASSES)}


def coco_categories() -> list[dict[str, Any]]:
    return [
        {
            "id": CATEGORY_IDS[name],
            "name": name,
            "supercategory": "structure" if name in STRUCTURAL_CLASSES else "object",
        }
        for name in NYU40_CLASSES
    ]


def coco_rle(mask: np.ndarray) -> dict[str, Any]:
    """COCO's uncompressed RLE of a bool (H, W) mask: runs over the column-major pixels,
    the first a (maybe empty) run of background."""
    height, width = mask.shape
    flat = mask.reshape(-1, order="F").astype(np.int8)
    change = np.flatnonzero(np.diff(flat)) + 1
    runs = np.diff(np.concatenate([[0], change, [flat.size]])).tolist()
    if flat.size and flat[0]:
        runs = [0, *runs]
    return {"counts": runs, "size": [height, width]}


def decode_coco_rle(rle: dict[str, Any]) -> np.ndarray:
    """The bool (H, W) mask of a COCO uncompressed RLE."""
    height, width = rle["size"]
    values = np.arange(len(rle["counts"])) % 2 == 1
    flat = np.repeat(values, rle["counts"])
    if flat.size != height * width:
        raise ValueError(f"RLE counts add up to {flat.size}, not {height}x{width}")
    return flat.reshape((height, width), order="F")


def _annotation(
    obj: SceneObject, number: int, width: int, height: int, image_id: int = 1
) -> dict[str, Any]:
    x1, y1, x2, y2 = obj.bbox
    segmentation: dict[str, Any] | list[list[float]]
    area: float
    if obj.mask is not None:
        pixels = decode_mask(obj.mask, width, height)
        segmentation, area = coco_rle(pixels), int(pixels.sum())
    else:
        segmentation = [[x1, y1, x2, y1, x2, y2, x1, y2]]
        area = (x2 - x1) * (y2 - y1)
    return {
        "id": number,
        "image_id": image_id,
        "category_id": CATEGORY_IDS[obj.cls],
        "bbox": [x1, y1, x2 - x1, y2 - y1],
        "area": area,
        "iscrowd": 0,
        "segmentation": segmentation,
        "holiscene_id": obj.id,
    }


def coco_instances(scene: Scene, description: str | None = None) -> dict[str, Any]:
    """The COCO instances file of the scene's photo (image id 1, annotation ids from 1)."""
    width, height = scene.image.width, scene.image.height
    return {
        "info": {"description": description or f"HoliScene scene {scene.name}", "version": "1"},
        "images": [{"id": 1, "file_name": scene.image.file, "width": width, "height": height}],
        "categories": coco_categories(),
        "annotations": [
            _annotation(obj, number, width, height)
            for number, obj in enumerate(scene.objects, start=1)
        ],
    }


def coco_dataset(scenes: Sequence[tuple[Scene, str]], description: str) -> dict[str, Any]:
    """One COCO instances file of several scenes, each (scene, its image's file name): image
    ids from 1 in order, annotation ids from 1 across them, supports in `holiscene_support`."""
    images: list[dict[str, Any]] = []
    annotations: list[dict[str, Any]] = []
    for image_id, (scene, file_name) in enumerate(scenes, start=1):
        width, height = scene.image.width, scene.image.height
        images.append({"id": image_id, "file_name": file_name, "width": width, "height": height})
        supports = {s.child: s for s in scene.supports}
        for obj in scene.objects:
            annotation = _annotation(obj, len(annotations) + 1, width, height, image_id)
            support = supports.get(obj.id)
            if support is not None:
                annotation["holiscene_support"] = {
                    "parent": support.parent,
                    "type": support.type,
                    **support_provenance(support),
                }
            annotations.append(annotation)
    return {
        "info": {"description": description, "version": "1"},
        "images": images,
        "categories": coco_categories(),
        "annotations": annotations,
    }
