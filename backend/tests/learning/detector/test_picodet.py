"""The committed PicoDet detector and the wrapper that puts it behind the detector contract."""

from __future__ import annotations

import hashlib
import json
from pathlib import Path

import cv2
import numpy as np
import onnx
import onnxruntime as ort
import pytest
from holiscene.learning.detector.picodet_contract import (
    PICODET_INPUT,
    PicoDetGraphError,
    input_model,
    wrap_picodet,
)
from holiscene.learning.detector.runtime import PICODET_DETECTOR_DIR, box_iou, preprocess
from holiscene_schema.detector_model import COCO_CLASSES, INPUT_NAME, MAX_DETECTIONS, OUTPUT_NAME
from onnx import TensorProto, helper

MODEL = PICODET_DETECTOR_DIR / "model.onnx"


def _rows(rgb: np.ndarray) -> np.ndarray:
    session = ort.InferenceSession(str(MODEL), providers=["CPUExecutionProvider"])
    out = np.asarray(session.run([OUTPUT_NAME], {INPUT_NAME: preprocess(rgb)})[0])
    assert out.shape == (1, MAX_DETECTIONS, 6)
    return out[0]


def test_the_picodet_model_keeps_its_provenance_and_check() -> None:
    metadata = json.loads((PICODET_DETECTOR_DIR / "metadata.json").read_text())
    assert metadata["label_space"] == "coco80" and metadata["classes"] == list(COCO_CLASSES)
    assert metadata["provenance"]["package"] == "PyPI paddlelabel-ml==1.0.0"
    assert metadata["model_sha256"] == hashlib.sha256(MODEL.read_bytes()).hexdigest()
    check = metadata["check"]
    assert check["unmatched"] == 0 and check["detections_compared"] > 0
    assert max(check["max_score_difference"], check["max_box_difference_of_input_size"]) <= 1e-3
    assert "Apache License" in (PICODET_DETECTOR_DIR / "LICENSE").read_text()


def test_rows_are_best_first_and_already_suppressed_per_class(real_photos: Path) -> None:
    rgb = cv2.cvtColor(cv2.imread(str(real_photos / "t3d-1" / "img.jpg")), cv2.COLOR_BGR2RGB)
    rows = _rows(rgb)
    scores = rows[:, 4]
    assert np.all(np.diff(scores) <= 0), "rows best first"
    kept = rows[scores >= 0.1]
    chair = COCO_CLASSES.index("chair")
    assert (kept[:, 5] == chair).sum() >= 5, "a classroom full of chairs"
    for index, row in enumerate(kept):
        same = kept[index + 1 :][kept[index + 1 :, 5] == row[5]]
        if len(same):
            # The model's own NMS (IoU 0.6) ran: no two rows of a class overlap more.
            assert box_iou(row[:4], same[:, :4]).max() <= 0.6 + 1e-6


def test_rows_hold_whole_class_indices_and_scores_in_range() -> None:
    rows = _rows(np.random.default_rng(3).integers(0, 256, (300, 400, 3), dtype=np.uint8))
    assert np.all(rows[:, 5] == np.round(rows[:, 5])) and rows[:, 5].min() >= 0
    assert rows[:, 5].max() < len(COCO_CLASSES) and 0 <= rows[:, 4].min() <= rows[:, 4].max() <= 1


def test_the_input_model_is_the_front_of_the_wrapped_one() -> None:
    """What the conversion check feeds Paddle: the tensor the wrapped model sees inside."""
    rgb = np.full((1, 512, 512, 3), 255.0 * 0.485, np.float32)
    session = ort.InferenceSession(
        input_model().SerializeToString(), providers=["CPUExecutionProvider"]
    )
    normalised = np.asarray(session.run([PICODET_INPUT], {INPUT_NAME: rgb})[0])
    assert normalised.shape == (1, 3, 416, 416)
    assert np.abs(normalised[0, 0]).max() < 1e-5, "the red mean subtracted"
    assert normalised[0, 1].mean() == pytest.approx((0.485 - 0.456) / 0.224, abs=1e-5)


def test_a_graph_that_is_not_picodet_is_refused() -> None:
    identity = helper.make_graph(
        [helper.make_node("Identity", ["x"], ["y"])],
        "not_picodet",
        [helper.make_tensor_value_info("x", TensorProto.FLOAT, [1])],
        [helper.make_tensor_value_info("y", TensorProto.FLOAT, [1])],
    )
    with pytest.raises(PicoDetGraphError, match="expected inputs 'image' and 'scale_factor'"):
        wrap_picodet(helper.make_model(identity))
    two_inputs = helper.make_graph(
        [helper.make_node("Add", ["image", "scale_factor"], ["y"])],
        "no_nms",
        [
            helper.make_tensor_value_info("image", TensorProto.FLOAT, [1]),
            helper.make_tensor_value_info("scale_factor", TensorProto.FLOAT, [1]),
        ],
        [helper.make_tensor_value_info("y", TensorProto.FLOAT, [1])],
    )
    with pytest.raises(PicoDetGraphError, match="one NonMaxSuppression"):
        wrap_picodet(onnx.helper.make_model(two_inputs))
