"""Adding and removing objects by hand (or by accepting an object detector's suggestion).

An added object gets the mask it came with, or one cut with GrabCut in its box the way the
`masks_grabcut` stage cuts each box (the box's own pixels when the cut fails). It starts
without a supporter. A removed object takes its supporter with it, and the objects it
supported are left without one.
"""

from __future__ import annotations

import math
from collections.abc import MutableMapping

import numpy as np
from holiscene_schema import (
    STRUCTURAL_SUPPORTERS,
    AddObject,
    ImageInfo,
    Mask,
    SceneObject,
    SupportRelation,
    UnknownClassError,
    normalise_class_name,
)

from .pipeline.stages.grabcut import MIN_SIDE
from .rle import encode_mask
from .segmentation import grabcut_in_box


class ObjectEditError(ValueError):
    """An object edit that cannot apply (the message says why)."""


def new_object(
    edit: AddObject, image: ImageInfo, taken: set[str], photo: np.ndarray | None
) -> SceneObject:
    """The object an AddObject edit describes; `taken` holds the ids already in the scene,
    `photo` (RGB) is needed only when the edit has no mask."""
    _check_id(edit.id, taken)
    cls = _nyu40_class(edit)
    _check_box(edit, image)
    if edit.mask is not None:
        _check_mask_window(edit, edit.mask, image)
    return SceneObject(
        id=edit.id,
        cls=cls,
        source_class=edit.cls if edit.cls != cls else None,
        bbox=list(edit.bbox),
        mask=edit.mask if edit.mask is not None else _mask_for(edit, photo),
        score=edit.score,
        source=edit.source,
    )


def remove_object(
    object_id: str,
    objects: MutableMapping[str, SceneObject],
    supports: MutableMapping[str, SupportRelation],
) -> None:
    """Take the object out, with its supporter; the objects it supported lose theirs."""
    if object_id not in objects:
        raise ObjectEditError(f"cannot remove {object_id!r}: no such object in this scene")
    del objects[object_id]
    supports.pop(object_id, None)
    for child in [c for c, s in supports.items() if s.parent == object_id]:
        del supports[child]


def cut_mask(photo: np.ndarray, bbox: list[float]) -> Mask:
    """GrabCut's mask of the object in its box, as the masks stage cuts it; the box's pixels
    (source "box") when the box is too small to cut or the cut fails."""
    x1, y1, x2, y2 = bbox
    cut = grabcut_in_box(photo, bbox) if min(x2 - x1, y2 - y1) >= MIN_SIDE else None
    mask = encode_mask(cut, "grabcut") if cut is not None else None
    return mask if mask is not None else box_mask(bbox)


def box_mask(bbox: list[float]) -> Mask:
    """Every pixel the box touches."""
    x1, y1 = math.floor(bbox[0]), math.floor(bbox[1])
    x2, y2 = math.ceil(bbox[2]), math.ceil(bbox[3])
    width, height = x2 - x1, y2 - y1
    return Mask(origin=[x1, y1], size=[width, height], rle=[0, width * height], source="box")


def _mask_for(edit: AddObject, photo: np.ndarray | None) -> Mask:
    if photo is None:
        raise ValueError(f"object {edit.id!r} has no mask and no photo was given to cut one")
    return cut_mask(photo, edit.bbox)


def _check_id(object_id: str, taken: set[str]) -> None:
    if object_id in STRUCTURAL_SUPPORTERS:
        raise ObjectEditError(f"object id {object_id!r} is reserved for the room's structure")
    if object_id in taken:
        raise ObjectEditError(f"object id {object_id!r} is already used in this scene")


def _nyu40_class(edit: AddObject) -> str:
    try:
        return normalise_class_name(edit.cls)
    except UnknownClassError as error:
        raise ObjectEditError(f"object {edit.id!r}: {error}") from error


def _check_box(edit: AddObject, image: ImageInfo) -> None:
    x1, y1, x2, y2 = edit.bbox
    if not all(math.isfinite(v) for v in edit.bbox):
        raise ObjectEditError(f"object {edit.id!r}: box {edit.bbox} is not finite pixels")
    if not (x2 > x1 and y2 > y1):
        raise ObjectEditError(
            f"object {edit.id!r}: box {edit.bbox} is empty (it needs x2 > x1 and y2 > y1)"
        )
    if not (x1 >= 0 and y1 >= 0 and x2 <= image.width and y2 <= image.height):
        raise ObjectEditError(
            f"object {edit.id!r}: box {edit.bbox} is not inside the "
            f"{image.width}x{image.height} photo"
        )


def _check_mask_window(edit: AddObject, mask: Mask, image: ImageInfo) -> None:
    (x, y), (width, height) = mask.origin, mask.size
    inside = x >= 0 and y >= 0 and x + width <= image.width and y + height <= image.height
    if width <= 0 or height <= 0 or not inside:
        raise ObjectEditError(
            f"object {edit.id!r}: mask window at {mask.origin} of size {mask.size} is not "
            f"inside the {image.width}x{image.height} photo"
        )
