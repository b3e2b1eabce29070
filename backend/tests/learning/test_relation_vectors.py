"""The Relation Network's shared vectors (shared_schema/vectors/relation_model.json) on the
Python side: preprocessing reproduces the stored tensors, onnxruntime on the committed default
model reproduces the stored logits, and the vectors were made from that very model file.
The browser side is checked against the same file by frontend/src/inference/preprocess.test.ts
and e2e_tests/tests/relation-network.spec.ts."""

from __future__ import annotations

import base64
import json
from functools import cache
from typing import Any

import numpy as np
import onnxruntime as ort
import pytest
from holiscene.twin_vectors import relation_model as rv
from holiscene_schema.relation_model import (
    IMAGE_SIZE,
    INPUT_NAMES,
    MASK_SIZE,
    OUTPUT_NAME,
    STRUCTURAL_COLUMNS,
    SUPPORT_TYPE_ORDER,
)
from holiscene_schema.scene import ImageInfo, Scene, SceneObject

INPUT_TOL = 1e-6
LOGIT_TOL = 1e-4


@cache
def vector_file() -> dict[str, Any]:
    data: dict[str, Any] = json.loads(rv.RELATION_VECTORS.read_text())
    return data


def cases() -> list[Any]:
    return [pytest.param(c, id=c["name"]) for c in vector_file()["cases"]]


def case_scene(case: dict[str, Any]) -> tuple[Scene, np.ndarray]:
    """The case's scene and RGB photo, from the file alone."""
    width, height = case["image"]["width"], case["image"]["height"]
    raw = base64.b64decode(case["image"]["rgb_base64"])
    image = np.frombuffer(raw, dtype=np.uint8).reshape(height, width, 3)
    scene = Scene(
        name=case["name"],
        image=ImageInfo(file="img.png", width=width, height=height),
        objects=[SceneObject.model_validate(o) for o in case["objects"]],
    )
    return scene, image


def expected_array(case: dict[str, Any], name: str) -> np.ndarray:
    entry = case["expected"][name]
    return np.asarray(entry["data"]).reshape(entry["shape"])


@cache
def session() -> ort.InferenceSession:
    return ort.InferenceSession(str(rv.DEFAULT_MODEL_FILE), providers=["CPUExecutionProvider"])


def test_vectors_come_from_the_committed_model() -> None:
    model = vector_file()["model"]
    assert rv.DEFAULT_MODEL_FILE.is_file(), f"no default model at {rv.DEFAULT_MODEL_FILE}"
    assert model["path"] == rv.DEFAULT_MODEL_FILE.relative_to(rv.REPO_ROOT).as_posix()
    assert model["sha256"] == rv.sha256(rv.DEFAULT_MODEL_FILE), (
        "the vectors are stale: run `make relation-vectors` after changing the default model"
    )


def test_vector_file_follows_the_contract() -> None:
    data = vector_file()
    assert rv.RELATION_VECTORS.stat().st_size < 1_500_000
    assert data["tolerance"] == {"inputs": INPUT_TOL, "support_logits": LOGIT_TOL}
    counts = []
    for case in data["cases"]:
        n = len(case["model_objects"])
        counts.append(n)
        shapes = {k: v["shape"] for k, v in case["expected"].items()}
        assert shapes == {
            "image": [1, 3, IMAGE_SIZE, IMAGE_SIZE],
            "masks": [n, MASK_SIZE, MASK_SIZE],
            "boxes": [n, 4],
            "classes": [n],
            OUTPUT_NAME: [n, n + len(STRUCTURAL_COLUMNS), len(SUPPORT_TYPE_ORDER)],
        }
        for entry in case["expected"].values():
            assert len(entry["data"]) == np.prod(entry["shape"])
    assert {1, 3, 20} <= set(counts)
    # Both paths of the scene -> objects step are exercised: a structural object left out and
    # objects whose box stands in for a mask.
    objects = [o for c in data["cases"] for o in c["objects"]]
    assert any(o["class"] in STRUCTURAL_COLUMNS for o in objects)
    assert any(o["mask"] is None for o in objects)


@pytest.mark.parametrize("case", cases())
def test_preprocessing_reproduces_the_vectors(case: dict[str, Any]) -> None:
    ids, inputs = rv.model_inputs(*case_scene(case))
    assert ids == case["model_objects"]
    for name in INPUT_NAMES:
        assert inputs[name].shape == tuple(case["expected"][name]["shape"])
    assert inputs["classes"].dtype == np.int64
    np.testing.assert_array_equal(inputs["classes"], expected_array(case, "classes"))
    for name in ("image", "masks", "boxes"):
        assert inputs[name].dtype == np.float32
        np.testing.assert_allclose(
            inputs[name], expected_array(case, name), rtol=0, atol=INPUT_TOL, err_msg=name
        )


@pytest.mark.parametrize("case", cases())
def test_onnxruntime_reproduces_the_logits(case: dict[str, Any]) -> None:
    _, inputs = rv.model_inputs(*case_scene(case))
    (logits,) = session().run([OUTPUT_NAME], {k: inputs[k] for k in INPUT_NAMES})
    expected = expected_array(case, OUTPUT_NAME)
    assert logits.shape == expected.shape
    np.testing.assert_allclose(logits, expected, rtol=0, atol=LOGIT_TOL)
