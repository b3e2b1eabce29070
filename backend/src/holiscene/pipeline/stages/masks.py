"""Masks from 2D boxes: each box's pixels, overlaps given to the object in front."""

from __future__ import annotations

import functools

import numpy as np
from holiscene_schema import SceneObject

from ..base import ObjectMask, SceneContext, Stage, required
from ..registry import register_stage

# A box lying this much inside another is taken to be in front of it (a pillow on a bed).
_CONTAINED = 0.7


def _area(b: list[float]) -> float:
    return max(0.0, b[2] - b[0]) * max(0.0, b[3] - b[1])


def _overlap(a: list[float], b: list[float]) -> float:
    w = min(a[2], b[2]) - max(a[0], b[0])
    h = min(a[3], b[3]) - max(a[1], b[1])
    return max(0.0, w) * max(0.0, h)


def _front_to_back(a: SceneObject, b: SceneObject) -> int:
    """Negative when a is in front of b. Contained boxes are in front; otherwise the box
    reaching lower in the image (nearer floor contact) is."""
    inter = _overlap(a.bbox, b.bbox)
    if inter > 0:
        if inter >= _CONTAINED * _area(a.bbox) and _area(a.bbox) < _area(b.bbox):
            return -1
        if inter >= _CONTAINED * _area(b.bbox) and _area(b.bbox) < _area(a.bbox):
            return 1
    return -1 if a.bbox[3] > b.bbox[3] else (1 if a.bbox[3] < b.bbox[3] else 0)


def occlusion_order(objects: list[SceneObject]) -> list[SceneObject]:
    """Objects from the frontmost to the backmost.

    A sort by the pairwise rule is not enough: the rule is not transitive (a box inside
    another is in front, otherwise the one reaching lower is), so a sort can put a box behind
    the box containing it, whose mask then swallows it. Only overlapping boxes need an order:
    the sorted list is repaired by moving each box after the boxes that must be in front of
    it (keeping the sorted order where the rule leaves a cycle).
    """
    in_front: dict[str, set[str]] = {obj.id: set() for obj in objects}
    for i, a in enumerate(objects):
        for b in objects[i + 1 :]:
            if _overlap(a.bbox, b.bbox) > 0 and (side := _front_to_back(a, b)) != 0:
                front, back = (a, b) if side < 0 else (b, a)
                in_front[back.id].add(front.id)
    remaining = sorted(objects, key=functools.cmp_to_key(_front_to_back))
    order: list[SceneObject] = []
    placed: set[str] = set()
    while remaining:
        ready = next((o for o in remaining if in_front[o.id] <= placed), remaining[0])
        remaining.remove(ready)
        order.append(ready)
        placed.add(ready.id)
    return order


def box_pixels(bbox: list[float], width: int, height: int) -> np.ndarray:
    x1, y1, x2, y2 = (round(v) for v in bbox)
    mask = np.zeros((height, width), dtype=bool)
    mask[max(0, y1) : min(height, y2), max(0, x1) : min(width, x2)] = True
    return mask


@register_stage
class MasksFromBoxes(Stage):
    name = "masks_from_boxes"
    requires = frozenset({"objects", "image"})
    provides = frozenset({"masks"})

    def run(self, ctx: SceneContext) -> None:
        taken = np.zeros((ctx.height, ctx.width), dtype=bool)
        masks: dict[str, ObjectMask] = {}
        for obj in occlusion_order(required(ctx.objects, "objects")):
            own = box_pixels(obj.bbox, ctx.width, ctx.height)
            visible = own & ~taken
            # A fully hidden object keeps its whole box, so every object has a mask.
            masks[obj.id] = ObjectMask(visible if visible.any() else own, source="box")
            taken |= own
        ctx.masks = masks
        ctx.notes[self.name] = "masks are box regions split by occlusion order (no GrabCut yet)"
