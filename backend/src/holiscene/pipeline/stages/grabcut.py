"""Masks from 2D boxes with GrabCut, overlaps resolved front to back."""

from __future__ import annotations

import os
from concurrent.futures import ThreadPoolExecutor

import numpy as np
from holiscene_schema import SceneObject

from ...segmentation import grabcut_in_box
from ...segmentation.rle import decode_mask
from ..base import ObjectMask, SceneContext, Stage, required
from ..registry import register_stage
from .masks import box_pixels, occlusion_order

# Boxes with a shorter side than this keep their box pixels: too few pixels for colour models.
MIN_SIDE = 12


@register_stage
class MasksGrabCut(Stage):
    name = "masks_grabcut"
    requires = frozenset({"objects", "image"})
    provides = frozenset({"masks"})

    def run(self, ctx: SceneContext) -> None:
        drawn = kept_masks(ctx)
        objects = occlusion_order(
            [o for o in required(ctx.objects, "objects") if o.id not in drawn]
        )
        # Each box is cut on its own, so the cuts run in parallel (OpenCV releases the GIL).
        # Fixing front masks as background for the boxes behind was tried: it carried the
        # front masks' errors backwards and scored worse on the synthetic scenes.
        with ThreadPoolExecutor(max_workers=os.cpu_count() or 1) as pool:
            cuts = list(pool.map(lambda obj: _cut(ctx.image, obj), objects))
        # Masks people drew or a dataset gave are kept as they are and claim their pixels first.
        masks: dict[str, ObjectMask] = dict(drawn)
        taken = np.zeros((ctx.height, ctx.width), dtype=bool)
        for mask in drawn.values():
            taken |= mask.pixels
        for obj, cut in zip(objects, cuts, strict=True):
            box = box_pixels(obj.bbox, ctx.width, ctx.height)
            free = box & ~taken  # front objects have claimed the rest
            pixels = free if cut is None else cut & free
            # Fallbacks so every object has a mask: its unclaimed box, else its whole box.
            if not pixels.any():
                pixels = free if free.any() else box
            masks[obj.id] = ObjectMask(pixels, source="grabcut")
            taken |= pixels
        ctx.masks = {o.id: masks[o.id] for o in required(ctx.objects, "objects")}
        uncut = {obj.id for obj, cut in zip(objects, cuts, strict=True) if cut is None}
        if uncut:
            ids = ", ".join(o.id for o in required(ctx.objects, "objects") if o.id in uncut)
            ctx.notes[self.name] = (
                f"{len(uncut)} of {len(objects)} objects keep their unclaimed box, too small or "
                f"not separable from their surroundings by colour: {ids}"
            )


def _cut(image: np.ndarray, obj: SceneObject) -> np.ndarray | None:
    """GrabCut's mask for the object; None for a box too small to cut or a failed cut."""
    x1, y1, x2, y2 = obj.bbox
    if min(x2 - x1, y2 - y1) < MIN_SIDE:
        return None
    return grabcut_in_box(image, obj.bbox)


def kept_masks(ctx: SceneContext) -> dict[str, ObjectMask]:
    """The masks this run keeps as they are, by object id: the ones people drew (a
    `set_by_person` mask) and the ones given with the boxes (an imported dataset's outlines,
    source "given")."""
    return {
        o.id: ObjectMask(decode_mask(o.mask, ctx.width, ctx.height), source=o.mask.source)
        for o in ctx.objects or []
        if o.mask is not None and ("mask" in o.set_by_person or o.mask.source == "given")
    }
