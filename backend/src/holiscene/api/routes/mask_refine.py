"""The mask tools' refine call: GrabCut in a box steered by strokes; nothing is stored."""

from __future__ import annotations

import time
from functools import lru_cache
from pathlib import Path

import numpy as np
from fastapi import APIRouter
from holiscene_schema import ErrorMessage, MaskRefineRequest, MaskRefineResult, Stroke

from ...inputs import load_photo
from ...segmentation.refine import BrushStroke, RefineInputError, check_refine_input, refine_in_box
from ...segmentation.rle import encode_mask
from ..deps import AnnotatorDep, WorkbenchDep

router = APIRouter(prefix="/api/scenes", tags=["scenes"])


@lru_cache(maxsize=4)
def _photo_rgb(path: Path, modified_ns: int) -> np.ndarray:
    """Decoded once per photo: a person refines one object many times in a row, and decoding a
    large JPEG would take most of the time the cut may have."""
    del modified_ns  # part of the key only: a replaced file is decoded again
    return load_photo(path.read_bytes()).rgb


def _brush(strokes: list[Stroke]) -> list[BrushStroke]:
    return [BrushStroke(points=s.points, radius=s.radius) for s in strokes]


@router.post(
    "/{scene_id}/mask-refine",
    response_model=MaskRefineResult,
    responses={404: {"model": ErrorMessage}, 422: {"model": ErrorMessage}},
)
def refine_mask(
    scene_id: str, request: MaskRefineRequest, workbench: WorkbenchDep, _: AnnotatorDep
) -> MaskRefineResult:
    """The object's mask in `bbox` from GrabCut, with the pixels under foreground strokes
    fixed as the object and under background strokes as not (source 'manual'). 422 for a box
    or stroke outside the photo, an empty box, or strokes that leave nothing."""
    path = workbench.scenes.image_path(scene_id)  # 404 for an unknown scene
    image = _photo_rgb(path, path.stat().st_mtime_ns)
    height, width = image.shape[:2]
    foreground, background = _brush(request.foreground), _brush(request.background)
    check_refine_input(width, height, request.bbox, foreground, background)
    start = time.perf_counter()
    pixels = refine_in_box(image, request.bbox, foreground, background)
    milliseconds = (time.perf_counter() - start) * 1000
    mask = encode_mask(pixels, "manual")
    if mask is None:
        raise RefineInputError(
            "the background strokes cover the whole object: nothing of it is left in the box"
        )
    return MaskRefineResult(mask=mask, milliseconds=milliseconds)
