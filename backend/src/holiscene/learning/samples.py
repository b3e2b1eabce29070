"""Labelled scenes as training and evaluation samples for the Relation Network.

A sample is the model's input tensors plus, per object, the index of its true answer in the
flattened (N + 3) x 2 output row (supporter column * 2 + type index), or -1 when the object
has no labelled supporter (it is then ignored by the loss and by accuracy).
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np
from holiscene_schema import STRUCTURAL_CLASSES, Scene
from holiscene_schema.relation_model import STRUCTURAL_COLUMNS, SUPPORT_TYPE_ORDER

from ..segmentation.rle import decode_mask
from .preprocess import relation_inputs

NO_LABEL = -1


@dataclass(frozen=True)
class SupportSample:
    name: str
    inputs: dict[str, np.ndarray]  # the contract's input tensors
    object_ids: tuple[str, ...]
    classes: tuple[str, ...]
    targets: np.ndarray  # int64 (N,): flattened answer index or NO_LABEL

    @property
    def labelled(self) -> int:
        return int((self.targets != NO_LABEL).sum())


def answer_index(column: int, support_type: str) -> int:
    return column * len(SUPPORT_TYPE_ORDER) + SUPPORT_TYPE_ORDER.index(support_type)


def supporter_column(parent: str, object_ids: Sequence[str]) -> int | None:
    """The output column of a supporter: an object's index, or N + its structural index."""
    if parent in STRUCTURAL_COLUMNS:
        return len(object_ids) + STRUCTURAL_COLUMNS.index(parent)
    return object_ids.index(parent) if parent in object_ids else None


def decode_answer(index: int) -> tuple[int, str]:
    """(supporter column, support type) of a flattened answer index."""
    column, kind = divmod(index, len(SUPPORT_TYPE_ORDER))
    return column, SUPPORT_TYPE_ORDER[kind]


def object_masks(scene: Scene) -> list[np.ndarray]:
    """Each object's full-image mask; an object without one uses its 2D box."""
    width, height = scene.image.width, scene.image.height
    masks = []
    for obj in scene.objects:
        if obj.mask is not None:
            masks.append(decode_mask(obj.mask, width, height))
            continue
        box = np.zeros((height, width), dtype=bool)
        x0, y0, x1, y1 = (round(v) for v in obj.bbox)
        box[max(0, y0) : max(y0 + 1, y1), max(0, x0) : max(x0 + 1, x1)] = True
        masks.append(box)
    return masks


def sample_from_scene(scene: Scene, image: np.ndarray) -> SupportSample | None:
    """The sample of a labelled scene (RGB uint8 photo); None when it has no object to learn.

    Structural objects (a labelled wall or floor region) are left out: they are supporters
    by their class, not by a column of their own."""
    kept = [o for o in scene.objects if o.cls not in STRUCTURAL_CLASSES]
    if not kept:
        return None
    scene = scene.model_copy(update={"objects": kept})
    ids = tuple(o.id for o in kept)
    targets = np.full(len(ids), NO_LABEL, dtype=np.int64)
    for support in scene.supports:
        if support.child not in ids:
            continue
        column = supporter_column(support.parent, ids)
        if column is not None and column != ids.index(support.child):
            targets[ids.index(support.child)] = answer_index(column, support.type)
    inputs = relation_inputs(
        image, object_masks(scene), [o.bbox for o in kept], [o.cls for o in kept]
    )
    return SupportSample(scene.name, inputs, ids, tuple(o.cls for o in kept), targets)
