"""Object edits: adding, removing, reclassifying, reboxing, remasking and restoring objects.

An added object gets the mask it came with, or one cut with GrabCut in its box the way the
`masks_grabcut` stage cuts each box (the box's own pixels when the cut fails). It starts
without a supporter. A removed object takes its supporter with it, and the objects it
supported are left without one. What a person set is recorded in `set_by_person`, so a
pipeline re-run keeps it (pipeline/people.py).
"""

from __future__ import annotations

import math
from collections.abc import MutableMapping, Sequence

import numpy as np
from holiscene_schema import (
    STRUCTURAL_SUPPORTERS,
    AddObject,
    ImageInfo,
    Mask,
    Scene,
    SceneObject,
    SupportRelation,
    UnknownClassError,
    normalise_class_name,
)

from ..pipeline.stages.grabcut import MIN_SIDE
from ..segmentation import grabcut_in_box
from ..segmentation.rle import decode_mask, encode_mask

PersonSet = str  # one of SceneObject.set_by_person's values

# Masks made from the box alone: a new box cuts them again. Others (a person's, a dataset's,
# the synthetic ground truth) are kept, clipped to the new box.
BOX_MADE_MASKS = frozenset({"box", "grabcut", "model"})


class ObjectEditError(ValueError):
    """An object edit that cannot apply (the message says why)."""


def new_object(
    edit: AddObject, image: ImageInfo, taken: set[str], photo: np.ndarray | None
) -> SceneObject:
    """The object an AddObject edit describes; `taken` holds the ids already in the scene,
    `photo` (RGB) is needed only when the edit has no mask."""
    _check_id(edit.id, taken)
    cls = nyu40_class(edit.id, edit.cls)
    check_box(edit.id, edit.bbox, image)
    if edit.mask is not None:
        check_mask_window(edit.id, edit.mask, image)
    return SceneObject(
        id=edit.id,
        cls=cls,
        source_class=edit.cls if edit.cls != cls else None,
        bbox=list(edit.bbox),
        mask=edit.mask if edit.mask is not None else _mask_for(edit, photo),
        score=edit.score,
        source=edit.source,
        set_by_person=["object"],
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


def with_class(obj: SceneObject, name: str) -> SceneObject:
    """The object with another class (an NYU-40 class or an alias of one)."""
    cls = nyu40_class(obj.id, name)
    return obj.model_copy(
        update={
            "cls": cls,
            "source_class": name if name != cls else None,
            "set_by_person": _marked(obj, "class"),
        }
    )


def with_bbox(
    obj: SceneObject, bbox: Sequence[float], image: ImageInfo, photo: np.ndarray | None
) -> SceneObject:
    """The object in a new box: a mask made from the box is cut again in it; any other mask is
    clipped to it (cut again if nothing of it is left inside)."""
    check_box(obj.id, bbox, image)
    box = [float(v) for v in bbox]
    mask = obj.mask
    clipped = None
    if mask is not None and mask.source not in BOX_MADE_MASKS:
        clipped = clip_mask(mask, box, image)
    if clipped is None:
        if photo is None:
            raise ValueError(f"object {obj.id!r} needs the photo to cut a mask in its new box")
        clipped = cut_mask(photo, box)
    return obj.model_copy(
        update={"bbox": box, "mask": clipped, "set_by_person": _marked(obj, "bbox")}
    )


def with_mask(obj: SceneObject, mask: Mask, image: ImageInfo) -> SceneObject:
    """The object with a mask a person drew (source "manual"); its box becomes the mask's
    extent, so box and mask never disagree."""
    check_mask_window(obj.id, mask, image)
    pixels = decode_mask(mask, image.width, image.height)
    drawn = encode_mask(pixels, "manual")
    if drawn is None:
        raise ObjectEditError(
            f"object {obj.id!r}: the mask has no pixels (remove the object instead)"
        )
    (x, y), (width, height) = drawn.origin, drawn.size
    return obj.model_copy(
        update={
            "mask": drawn,
            "bbox": [float(x), float(y), float(x + width), float(y + height)],
            "set_by_person": _marked(obj, "mask", "bbox"),
        }
    )


def restore_object(
    object_id: str,
    earlier: Scene,
    objects: dict[str, SceneObject],
    supports: MutableMapping[str, SupportRelation],
) -> dict[str, SceneObject]:
    """The objects with `object_id` as it was in `earlier` (removed if `earlier` lacked it),
    with the supports it took part in there: its own, and those of objects it held up that
    are still here and have no supporter now (a supporter set since is a newer decision).
    Returns the objects in their new order: a restored object goes back to its place."""
    before = next((o for o in earlier.objects if o.id == object_id), None)
    if before is None:
        if object_id in objects:
            remove_object(object_id, objects, supports)
        return objects
    present = set(objects) | {object_id}
    restored = _in_earlier_order(objects, before, [o.id for o in earlier.objects])
    supports.pop(object_id, None)
    for support in earlier.supports:
        if not _within(support, present):
            continue
        if support.child == object_id or (
            support.parent == object_id and support.child not in supports
        ):
            supports[support.child] = support
    return restored


def clip_mask(mask: Mask, bbox: Sequence[float], image: ImageInfo) -> Mask | None:
    """The mask's pixels inside the box (same source); None when none are left."""
    pixels = decode_mask(mask, image.width, image.height)
    x1, y1 = math.floor(bbox[0]), math.floor(bbox[1])
    x2, y2 = math.ceil(bbox[2]), math.ceil(bbox[3])
    inside = np.zeros_like(pixels)
    inside[y1:y2, x1:x2] = True
    return encode_mask(pixels & inside, mask.source)


def cut_mask(photo: np.ndarray, bbox: Sequence[float]) -> Mask:
    """GrabCut's mask of the object in its box, as the masks stage cuts it; the box's pixels
    (source "box") when the box is too small to cut or the cut fails."""
    x1, y1, x2, y2 = bbox
    cut = grabcut_in_box(photo, list(bbox)) if min(x2 - x1, y2 - y1) >= MIN_SIDE else None
    mask = encode_mask(cut, "grabcut") if cut is not None else None
    return mask if mask is not None else box_mask(bbox)


def box_mask(bbox: Sequence[float]) -> Mask:
    """Every pixel the box touches."""
    x1, y1 = math.floor(bbox[0]), math.floor(bbox[1])
    x2, y2 = math.ceil(bbox[2]), math.ceil(bbox[3])
    width, height = x2 - x1, y2 - y1
    return Mask(origin=[x1, y1], size=[width, height], rle=[0, width * height], source="box")


def nyu40_class(object_id: str, name: str) -> str:
    try:
        return normalise_class_name(name)
    except UnknownClassError as error:
        raise ObjectEditError(f"object {object_id!r}: {error}") from error


def check_box(object_id: str, bbox: Sequence[float], image: ImageInfo) -> None:
    x1, y1, x2, y2 = bbox
    if not all(math.isfinite(v) for v in bbox):
        raise ObjectEditError(f"object {object_id!r}: box {list(bbox)} is not finite pixels")
    if not (x2 > x1 and y2 > y1):
        raise ObjectEditError(
            f"object {object_id!r}: box {list(bbox)} is empty (it needs x2 > x1 and y2 > y1)"
        )
    if not (x1 >= 0 and y1 >= 0 and x2 <= image.width and y2 <= image.height):
        raise ObjectEditError(
            f"object {object_id!r}: box {list(bbox)} is not inside the "
            f"{image.width}x{image.height} photo"
        )


def check_mask_window(object_id: str, mask: Mask, image: ImageInfo) -> None:
    (x, y), (width, height) = mask.origin, mask.size
    inside = x >= 0 and y >= 0 and x + width <= image.width and y + height <= image.height
    if width <= 0 or height <= 0 or not inside:
        raise ObjectEditError(
            f"object {object_id!r}: mask window at {mask.origin} of size {mask.size} is not "
            f"inside the {image.width}x{image.height} photo"
        )


def _mask_for(edit: AddObject, photo: np.ndarray | None) -> Mask:
    if photo is None:
        raise ValueError(f"object {edit.id!r} has no mask and no photo was given to cut one")
    return cut_mask(photo, edit.bbox)


def _check_id(object_id: str, taken: set[str]) -> None:
    if object_id in STRUCTURAL_SUPPORTERS:
        raise ObjectEditError(f"object id {object_id!r} is reserved for the room's structure")
    if object_id in taken:
        raise ObjectEditError(f"object id {object_id!r} is already used in this scene")


def _marked(obj: SceneObject, *parts: PersonSet) -> list[PersonSet]:
    return [*obj.set_by_person, *(p for p in parts if p not in obj.set_by_person)]


def _within(support: SupportRelation, ids: set[str]) -> bool:
    return support.child in ids and (
        support.parent in ids or support.parent in STRUCTURAL_SUPPORTERS
    )


def _in_earlier_order(
    objects: dict[str, SceneObject], restored: SceneObject, earlier_order: list[str]
) -> dict[str, SceneObject]:
    """The objects with `restored` in its earlier place: after the nearest object that came
    before it then and is still here (first if none)."""
    rest = {k: v for k, v in objects.items() if k != restored.id}
    index = earlier_order.index(restored.id)
    anchor = next((i for i in reversed(earlier_order[:index]) if i in rest), None)
    ordered: dict[str, SceneObject] = {} if anchor is not None else {restored.id: restored}
    for key, value in rest.items():
        ordered[key] = value
        if key == anchor:
            ordered[restored.id] = restored
    return ordered
