"""The object detector's shared vectors (shared_schema/vectors/detector_model.json) on the Python
side: the photos stretch to the stored input tensor (bit for bit, by its sha256), onnxruntime
on the committed default detector reproduces the stored raw rows (within 1e-4: scores, and box
corners as shares of the input size), decoding reproduces the stored boxes, and the vectors
were made from that very model file; the same for the scene page's suggester
(suggester_model.json). The browser side is checked against
the same file by frontend/src/inference/detectorTensor.test.ts and
e2e_tests/tests/detector-model.spec.ts."""

from __future__ import annotations

import hashlib
import json
import math
from functools import cache
from typing import Any

import numpy as np
import pytest
from holiscene.learning.detector.row_matching import unmatched_rows
from holiscene.learning.detector.runtime import (
    DEFAULT_DETECTOR_DIR,
    MODEL_FILE,
    SUGGESTER_DETECTOR_DIR,
    DetectedBox,
    Detector,
    decode,
    preprocess,
)
from holiscene.twin_vectors import detector_model as dv
from holiscene_schema.detector_model import (
    COCO_CLASSES,
    COCO_TO_NYU40,
    INPUT_NAME,
    INPUT_SIZE,
    MAX_DETECTIONS,
    MIN_BOX_PX,
    NMS_IOU,
    OUTPUT_NAME,
    SCORE_THRESHOLD,
)

INPUT_TOL = 1e-6
RAW_TOL = 1e-4
BOX_TOL = 1e-4


@cache
def vector_file() -> dict[str, Any]:
    data: dict[str, Any] = json.loads(dv.DETECTOR_VECTORS.read_text())
    return data


def cases() -> list[Any]:
    return [pytest.param(c, id=c["name"]) for c in vector_file()["cases"]]


def photos() -> list[Any]:
    """Every photo whose input tensor the file keeps (those the model runs on, and the rest)."""
    data = vector_file()
    return [pytest.param(c, id=c["name"]) for c in data["cases"] + data["preprocess_cases"]]


def decode_cases() -> list[Any]:
    return [pytest.param(c, id=c["name"]) for c in vector_file()["decode_cases"]]


@cache
def detector() -> Detector:
    return Detector(DEFAULT_DETECTOR_DIR)


def raw_rows(entry: dict[str, Any]) -> np.ndarray:
    return np.asarray(entry["data"], dtype=np.float32).reshape(entry["shape"])


def as_json(boxes: list[DetectedBox]) -> list[dict[str, Any]]:
    return [dv.box_json(b) for b in boxes]


def assert_same_boxes(actual: list[dict[str, Any]], expected: list[dict[str, Any]]) -> None:
    assert [(b["class"], b["source_class"]) for b in actual] == [
        (b["class"], b["source_class"]) for b in expected
    ]
    for a, e in zip(actual, expected, strict=True):
        np.testing.assert_allclose(a["bbox"], e["bbox"], rtol=0, atol=BOX_TOL)
        assert abs(a["score"] - e["score"]) <= BOX_TOL


def test_vectors_come_from_the_committed_model() -> None:
    model = vector_file()["model"]
    served = DEFAULT_DETECTOR_DIR / MODEL_FILE
    assert served.is_file(), f"no detector at {served}"
    # The same bytes, wherever they are (the default detector's folder, or the COCO model's).
    assert model["sha256"] == dv.sha256(served), (
        "the vectors are stale: run `make detector-vectors` after changing the default detector"
    )
    assert model["label_space"] == detector().metadata["label_space"]
    assert model["classes"] == detector().classes


def test_vector_file_follows_the_contract() -> None:
    data = vector_file()
    assert dv.DETECTOR_VECTORS.stat().st_size < 400_000
    assert data["tolerance"] == {"inputs": INPUT_TOL, "detections": RAW_TOL, "boxes": BOX_TOL}
    assert data["contract"] == {
        "input_size": INPUT_SIZE,
        "score_threshold": SCORE_THRESHOLD,
        "nms_iou": NMS_IOU,
        "min_box_px": MIN_BOX_PX,
    }
    sizes = set()
    for case in data["cases"] + data["preprocess_cases"]:
        image = dv.decoded_photo(case["image"])
        sizes.add(image.shape[:2])
        expected = case["expected"]
        assert expected[INPUT_NAME]["shape"] == [1, INPUT_SIZE, INPUT_SIZE, 3]
        samples = expected[INPUT_NAME]["samples"]
        assert len(samples["index"]) == len(samples["data"]) >= dv.SAMPLES
    for case in data["cases"]:
        assert case["expected"][OUTPUT_NAME]["shape"] == [1, MAX_DETECTIONS, 6]
        assert len(case["expected"][OUTPUT_NAME]["data"]) == MAX_DETECTIONS * 6
    # Photos smaller than the input, of odd sizes, a 4:3 photo; a pixel, a column, a row.
    assert {(30, 40), (61, 97), (480, 640)} <= {
        dv.decoded_photo(c["image"]).shape[:2] for c in data["cases"]
    }
    assert {(1, 1), (50, 1), (1, 70)} <= sizes
    # The decoded boxes at the low threshold are many (synthetic photos score low), so mapping
    # and NMS meet the model's real rows; the hand-made cases meet the contract's threshold.
    assert sum(len(c["expected"]["boxes_low_threshold"]) for c in data["cases"]) >= 20
    assert sum(len(c["expected"]) for c in data["decode_cases"]) >= 10


@pytest.mark.parametrize("case", photos())
def test_preprocessing_reproduces_the_vectors(case: dict[str, Any]) -> None:
    tensor = preprocess(dv.decoded_photo(case["image"]))
    expected = case["expected"][INPUT_NAME]
    assert tensor.dtype == np.float32 and list(tensor.shape) == expected["shape"]
    flat = tensor.reshape(-1)
    np.testing.assert_allclose(
        flat[expected["samples"]["index"]], expected["samples"]["data"], rtol=0, atol=INPUT_TOL
    )
    channels = tensor.reshape(-1, 3).astype(np.float64)
    means = [math.fsum(channels[:, c]) / len(channels) for c in range(3)]
    np.testing.assert_allclose(means, expected["channel_means"], rtol=0, atol=INPUT_TOL)
    digest = hashlib.sha256(flat.astype("<f4").tobytes()).hexdigest()
    assert digest == expected["float32_sha256"]


@pytest.mark.parametrize("case", cases())
def test_onnxruntime_reproduces_the_raw_rows(case: dict[str, Any]) -> None:
    raw = detector().raw(preprocess(dv.decoded_photo(case["image"])))
    expected = raw_rows(case["expected"][OUTPUT_NAME])
    assert raw.shape == expected.shape
    assert unmatched_rows(raw, expected, RAW_TOL) == []


@pytest.mark.parametrize("case", cases())
def test_decoding_the_stored_rows_reproduces_the_boxes(case: dict[str, Any]) -> None:
    d = detector()
    raw = raw_rows(case["expected"][OUTPUT_NAME])
    width, height = case["image"]["width"], case["image"]["height"]
    for key, threshold in (
        ("boxes", SCORE_THRESHOLD),
        ("boxes_low_threshold", vector_file()["low_threshold"]),
    ):
        boxes = decode(raw, width, height, d.classes, d.to_nyu40, threshold)
        assert_same_boxes(as_json(boxes), case["expected"][key])


@pytest.mark.parametrize("case", decode_cases())
def test_decoding_the_hand_made_rows_reproduces_the_boxes(case: dict[str, Any]) -> None:
    classes = case["classes"] or list(COCO_CLASSES)
    to_nyu: list[str | None] = case["classes"] or list(COCO_TO_NYU40)
    boxes = decode(
        raw_rows(case[OUTPUT_NAME]),
        case["width"],
        case["height"],
        classes,
        to_nyu,
        case["score_threshold"],
    )
    assert_same_boxes(as_json(boxes), case["expected"])


def test_hand_made_cases_meet_the_edges_they_name() -> None:
    by_name = {c["name"]: c["expected"] for c in vector_file()["decode_cases"]}
    edge = by_name["threshold-edge-and-class-indices"]
    # The row at the threshold is kept, the one just under it, the dog and the out-of-range
    # classes are not; 41.4 and 38.6 round to cup and bottle (both otherprop, far apart).
    assert sorted(b["source_class"] for b in edge) == ["bottle", "chair", "cup"]
    nms = by_name["nms-ties-and-limits"]
    chairs = [b["bbox"] for b in nms if b["class"] == "chair"]
    assert [0.0, 0.0, 100.0, 50.0] in chairs  # IoU exactly 0.5: kept
    assert [200.0, 200.0, 300.0, 251.0] not in chairs  # just over: suppressed
    sofas = [b["bbox"] for b in nms if b["class"] == "sofa"]
    assert sofas == [[300.0, 0.0, 400.0, 80.0]]  # equal scores: the earlier row
    assert [b["source_class"] for b in nms if b["class"] == "otherprop"] == ["bottle"]
    small = by_name["clip-and-small-boxes"]
    assert [b["class"] for b in small] == ["chair", "chair"]  # the couches went, both
    assert small[0]["bbox"][:2] == [0.0, 0.0] and small[1]["bbox"][2:] == [97.0, 61.0]
    nyu = by_name["nyu40-model"]
    assert [b["class"] for b in nyu] == ["table", "chair", "otherprop"]


def test_the_suggester_vectors_come_from_the_committed_suggester_and_hold() -> None:
    data = json.loads(dv.SUGGESTER_VECTORS.read_text())
    assert data["model"]["sha256"] == dv.sha256(SUGGESTER_DETECTOR_DIR / MODEL_FILE), (
        "the suggester's vectors are stale: run `make detector-vectors`"
    )
    suggester = Detector(SUGGESTER_DETECTOR_DIR)
    assert data["model"]["classes"] == suggester.classes
    named = 0
    for case in data["cases"]:
        tensor = preprocess(dv.decoded_photo(case["image"]))
        expected = case["expected"]
        assert (
            hashlib.sha256(tensor.astype("<f4").tobytes()).hexdigest()
            == (expected[INPUT_NAME]["float32_sha256"])
        )
        rows = raw_rows(expected[OUTPUT_NAME])
        assert unmatched_rows(suggester.raw(tensor), rows, RAW_TOL) == []
        width, height = case["image"]["width"], case["image"]["height"]
        boxes = decode(
            rows, width, height, suggester.classes, suggester.to_nyu40, data["low_threshold"]
        )
        assert_same_boxes(as_json(boxes), expected["boxes_low_threshold"])
        named += len(boxes)
    assert named > 0  # the low threshold's boxes exercise its classes' decoding
