"""The objects_from_detector stage: given boxes first, the detector for the rest."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest
from holiscene.evaluation.box_iou import iou_2d
from holiscene.inputs import read_input_folder
from holiscene.learning.detector.runtime import DEFAULT_DETECTOR_DIR, DetectedBox, Detector
from holiscene.pipeline import PipelineBuildError, build_pipeline
from holiscene.pipeline.base import SceneContext
from holiscene.pipeline.stages.detector import one_box_per_place
from holiscene_schema.detector_model import SAME_PLACE_IOU, SCORE_THRESHOLD


def _context(folder: Path, with_boxes: bool) -> SceneContext:
    inputs = read_input_folder(folder)
    return SceneContext(
        image=inputs.photo.rgb, detections=inputs.detections if with_boxes else None
    )


def test_given_boxes_are_kept_as_they_are(real_photos: Path) -> None:
    ctx = _context(real_photos / "mm3d-1", with_boxes=True)
    build_pipeline(["objects_from_detector"]).run(ctx)
    assert ctx.objects is not None and ctx.detections is not None
    assert [o.bbox for o in ctx.objects] == [list(d.bbox) for d in ctx.detections]
    assert {o.source for o in ctx.objects} == {"given"}


def test_without_boxes_the_detector_makes_the_objects(real_photos: Path) -> None:
    ctx = _context(real_photos / "mm3d-1", with_boxes=False)
    build_pipeline(["objects_from_detector"]).run(ctx)
    assert ctx.objects and all(o.source == "detector" for o in ctx.objects)
    assert [o.id for o in ctx.objects] == [f"o{i}" for i in range(len(ctx.objects))]
    scores = [o.score or 0.0 for o in ctx.objects]
    assert scores == sorted(scores, reverse=True) and min(scores) >= 0.3


def test_one_box_per_place_keeps_the_likeliest_class_there() -> None:
    bed = DetectedBox((0, 200, 268, 480), 0.8, "bed", "bed")
    sofa = DetectedBox((0, 205, 268, 480), 0.6, "sofa", "couch")
    chair = DetectedBox((600, 200, 640, 320), 0.7, "chair", "chair")
    # A pillow on the bed overlaps it a little: another place.
    pillow = DetectedBox((20, 210, 120, 280), 0.4, "pillow", "pillow")
    assert one_box_per_place([sofa, pillow, bed, chair]) == [bed, chair, pillow]


def _overlapping_pairs(boxes: list[list[float]]) -> int:
    return sum(iou_2d(a, b) > SAME_PLACE_IOU for i, a in enumerate(boxes) for b in boxes[i + 1 :])


def test_the_detector_makes_one_object_per_place(real_photos: Path) -> None:
    # The detector's NMS is per class; on these photos it boxes some things twice under two
    # classes (a bed also as a sofa), which would be two objects with one box.
    detector = Detector.load(DEFAULT_DETECTOR_DIR)
    twins = 0
    for name in ("t3d-1", "t3d-2", "im3d-5", "mm3d-1", "mm3d-3"):
        ctx = _context(real_photos / name, with_boxes=False)
        found = detector.detect(np.asarray(ctx.image), SCORE_THRESHOLD)
        twins += _overlapping_pairs([list(b.bbox) for b in found])
        build_pipeline(["objects_from_detector"]).run(ctx)
        assert ctx.objects, name
        assert _overlapping_pairs([o.bbox for o in ctx.objects]) == 0, name
    assert twins > 0


def test_add_missing_adds_only_what_the_given_boxes_lack(real_photos: Path) -> None:
    ctx = _context(real_photos / "mm3d-1", with_boxes=True)
    given = len(ctx.detections or [])
    stages = build_pipeline(
        ["objects_from_detector"], {"objects_from_detector": {"add_missing": True}}
    )
    stages.run(ctx)
    assert ctx.objects is not None
    added = ctx.objects[given:]
    assert all(o.source == "detector" for o in added)
    assert {o.source for o in ctx.objects[:given]} == {"given"}
    # Nothing added sits on a given box (IoU above the NMS threshold).
    alone = _context(real_photos / "mm3d-1", with_boxes=False)
    build_pipeline(["objects_from_detector"]).run(alone)
    assert alone.objects is not None and len(added) < len(alone.objects)


def test_bad_options_fail_when_the_pipeline_is_built(tmp_path: Path) -> None:
    with pytest.raises(PipelineBuildError, match="score_threshold"):
        build_pipeline(["objects_from_detector"], {"objects_from_detector": {"score_threshold": 0}})
    with pytest.raises(PipelineBuildError, match="no detector metadata"):
        build_pipeline(
            ["objects_from_detector"], {"objects_from_detector": {"model_dir": tmp_path}}
        )
