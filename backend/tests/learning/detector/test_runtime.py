"""The detector's runtime: the contract's preprocessing and decoding, and model loading."""

from __future__ import annotations

import json
import shutil
from pathlib import Path

import cv2
import numpy as np
import pytest
from holiscene.learning.detector.runtime import (
    COCO_DETECTOR_DIR,
    DEFAULT_DETECTOR_DIR,
    Detector,
    DetectorModelError,
    bilinear_resize,
    decode,
)
from holiscene.learning.runtime import DEFAULT_MODEL_DIR
from holiscene_schema import NYU40_CLASSES
from holiscene_schema.detector_model import COCO_CLASSES, COCO_TO_NYU40

CLASSES = list(COCO_CLASSES)
MAPPING = list(COCO_TO_NYU40)
CHAIR, COUCH, CAT = CLASSES.index("chair"), CLASSES.index("couch"), CLASSES.index("cat")


def _raw(*rows: tuple[float, float, float, float, float, int]) -> np.ndarray:
    raw = np.zeros((1, 100, 6), np.float32)
    for i, row in enumerate(rows):
        raw[0, i] = row
    return raw


def test_bilinear_resize_keeps_constants_and_samples_half_pixel_centres() -> None:
    flat = np.full((30, 40, 3), 77, np.uint8)
    assert np.all(bilinear_resize(flat, 16) == 77)
    ramp = np.tile(np.arange(4, dtype=np.uint8)[None, :, None] * 10, (2, 1, 3))
    # 4 columns to 2: output column c samples x = (c + 0.5) * 2 - 0.5 = 0.5, 2.5.
    assert bilinear_resize(ramp, 2)[0, :, 0].tolist() == [5.0, 25.0]


def test_decode_scales_clips_maps_and_suppresses_per_class() -> None:
    raw = _raw(
        (0, 0, 256, 256, 0.9, CHAIR),
        (10, 10, 266, 266, 0.8, CHAIR),  # the same chair again: suppressed
        (10, 10, 266, 266, 0.7, COUCH),  # another class in the same place: kept
        (300, 300, 600, 520, 0.6, CHAIR),  # overhangs the input: clipped
        (0, 0, 100, 100, 0.95, CAT),  # not an indoor class: dropped
        (0, 0, 100, 100, 0.2, CHAIR),  # under the threshold
        (50, 50, 51, 51, 0.9, COUCH),  # under 4 px once scaled
    )
    found = decode(raw, 1024, 512, CLASSES, MAPPING)
    assert [(d.cls, d.source_class) for d in found] == [
        ("chair", "chair"),
        ("sofa", "couch"),
        ("chair", "chair"),
    ]
    assert found[0].bbox == (0.0, 0.0, 512.0, 256.0)  # x * 1024 / 512, y * 512 / 512
    assert found[2].bbox == (600.0, 300.0, 1024.0, 512.0)
    assert found[1].score == pytest.approx(0.7)


def test_the_default_detector_finds_nyu40_objects_in_a_real_photo(real_photos: Path) -> None:
    rgb = cv2.cvtColor(cv2.imread(str(real_photos / "mm3d-1" / "img.jpg")), cv2.COLOR_BGR2RGB)
    found = Detector.load(DEFAULT_DETECTOR_DIR).detect(rgb)
    assert found, "no object found in a bedroom"
    height, width = rgb.shape[:2]
    for box in found:
        assert box.cls in NYU40_CLASSES and 0.3 <= box.score <= 1
        assert 0 <= box.bbox[0] < box.bbox[2] <= width and 0 <= box.bbox[1] < box.bbox[3] <= height


def test_the_coco_model_keeps_its_provenance() -> None:
    metadata = json.loads((COCO_DETECTOR_DIR / "metadata.json").read_text())
    assert metadata["label_space"] == "coco80" and metadata["classes"] == CLASSES
    assert "@vladmandic/human" in metadata["provenance"]["package"]
    assert metadata["check"]["max_score_difference"] <= 1e-3
    assert (COCO_DETECTOR_DIR / "LICENSE").read_text().startswith("MIT License")


def test_corrupt_or_wrong_shaped_models_are_refused_clearly(tmp_path: Path) -> None:
    corrupt = tmp_path / "corrupt"
    shutil.copytree(COCO_DETECTOR_DIR, corrupt)
    (corrupt / "model.onnx").write_bytes(b"not a model")
    with pytest.raises(DetectorModelError, match="cannot load detector model"):
        Detector(corrupt)
    wrong = tmp_path / "wrong"
    shutil.copytree(COCO_DETECTOR_DIR, wrong)
    shutil.copy(DEFAULT_MODEL_DIR / "model.onnx", wrong / "model.onnx")  # the Relation Network
    with pytest.raises(DetectorModelError, match="contract needs images"):
        Detector(wrong)
    (wrong / "metadata.json").write_text("{")
    with pytest.raises(DetectorModelError, match="not JSON"):
        Detector(wrong)
