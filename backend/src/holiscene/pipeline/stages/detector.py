"""Objects from the object detector when no boxes are given with the photo (and, on request,
the objects the given boxes lack)."""

from __future__ import annotations

from pathlib import Path
from typing import Any

import numpy as np
from holiscene_schema import SceneObject
from holiscene_schema.detector_model import (
    FLAT_PHOTO_STD,
    NMS_IOU,
    SAME_PLACE_IOU,
    SCORE_THRESHOLD,
)

from ...learning.detector.runtime import (
    DEFAULT_DETECTOR_DIR,
    DetectedBox,
    Detector,
    DetectorModelError,
    box_iou,
)
from ..base import PipelineBuildError, SceneContext, Stage
from ..people import keep_people_objects
from ..registry import register_stage
from .detections import NO_GIVEN_OBJECTS, objects_from_detections, unknown_class_note


@register_stage
class ObjectsFromDetector(Stage):
    """Given boxes become objects as they are (source "given"); without them the detector's
    boxes do (source "detector", with their score), one per place: of boxes of other classes
    at the same place (IoU over SAME_PLACE_IOU) the likeliest stands for it, so one bed does not
    become a bed, a sofa and a piece of furniture. `add_missing=True` also adds the detector's
    boxes that overlap no given box (IoU at most the NMS threshold)."""

    name = "objects_from_detector"
    requires = frozenset({"image", "detections"})
    provides = frozenset({"objects"})

    def __init__(
        self,
        model_dir: str | Path | None = None,
        score_threshold: float = SCORE_THRESHOLD,
        add_missing: bool = False,
        **rest: Any,
    ) -> None:
        super().__init__(**rest)
        if not 0.0 < score_threshold <= 1.0:
            raise PipelineBuildError(f"stage {self.name!r}: score_threshold must be in (0, 1]")
        try:
            self.detector = Detector.load(Path(model_dir) if model_dir else DEFAULT_DETECTOR_DIR)
        except DetectorModelError as error:
            raise PipelineBuildError(f"stage {self.name!r}: {error}") from None
        self.score_threshold = score_threshold
        self.add_missing = add_missing

    def run(self, ctx: SceneContext) -> None:
        given = objects_from_detections(ctx.detections or [])
        unknown = unknown_class_note(ctx.detections or [])
        if unknown:
            ctx.notes[self.name] = unknown
        if ctx.detections is not None and not self.add_missing:
            ctx.objects = keep_people_objects(given, ctx.pinned_objects, ctx.removed_objects)
            if not ctx.objects and not unknown:
                ctx.notes[self.name] = NO_GIVEN_OBJECTS
            return
        if _featureless(ctx.image):
            # A detector still "sees" something in a blank frame (PicoDet: a person at 0.31
            # in a black one); nothing there is an object.
            ctx.objects = keep_people_objects(given, ctx.pinned_objects, ctx.removed_objects)
            ctx.notes[self.name] = (
                "the photo is one flat colour, so the detector was not run: "
                "check the photo, or draw the objects' boxes"
            )
            return
        found = one_box_per_place(self.detector.detect(ctx.image, self.score_threshold))
        if given:
            found = [box for box in found if not _overlaps_any(box, given)]
        added = [
            SceneObject(
                id=f"o{len(given) + index}",
                cls=box.cls,
                source_class=box.source_class,
                bbox=list(box.bbox),
                score=round(box.score, 4),
                source="detector",
            )
            for index, box in enumerate(found)
        ]
        ctx.objects = keep_people_objects(given + added, ctx.pinned_objects, ctx.removed_objects)
        if not ctx.objects:
            ctx.notes[self.name] = (
                f"the detector found no objects (score at least {self.score_threshold:g}) "
                "and no boxes were given: draw the objects' boxes"
            )


def one_box_per_place(found: list[DetectedBox]) -> list[DetectedBox]:
    """The boxes, likeliest first, without those at the place of a likelier one (IoU over
    SAME_PLACE_IOU, whatever the classes)."""
    kept: list[DetectedBox] = []
    for box in sorted(found, key=lambda b: -b.score):
        places = np.array([k.bbox for k in kept], dtype=np.float64)
        if kept and box_iou(np.array(box.bbox), places).max() > SAME_PLACE_IOU:
            continue
        kept.append(box)
    return kept


def _featureless(image: np.ndarray) -> bool:
    return float(np.asarray(image, dtype=np.float32).mean(axis=2).std()) < FLAT_PHOTO_STD


def _overlaps_any(box: DetectedBox, objects: list[SceneObject]) -> bool:
    boxes = np.array([o.bbox for o in objects], dtype=np.float64)
    return bool(box_iou(np.array(box.bbox), boxes).max() > NMS_IOU)
