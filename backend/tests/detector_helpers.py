"""Helpers for the detector registry tests: stored scenes with boxes, detector folders."""

from __future__ import annotations

import json
import shutil
from pathlib import Path
from typing import Literal

from holiscene.inputs import InputFiles, load_photo
from holiscene.learning.detector.runtime import COCO_DETECTOR_DIR, METADATA_FILE, MODEL_FILE
from holiscene.store.scenes import SceneStore

from .model_helpers import _synthetic

# Synthetic rooms stored as scenes with boxes (no other test stores them).
BOXED_SEEDS = (4102, 4103, 4106, 4108)

ObjectSource = Literal["given", "detector", "manual"]


def store_boxed_scene(scenes: SceneStore, seed: int, source: ObjectSource = "manual") -> str:
    """A synthetic room with its true boxes, every object of the given source (and its true
    supports, set by a person)."""
    png, truth = _synthetic(seed)
    objects = [o.model_copy(update={"source": source}) for o in truth.objects]
    scene = truth.model_copy(update={"objects": objects})
    inputs = InputFiles(photo=load_photo(png), K=None, detections=None)
    return scenes.create(inputs, scene, "test").id


def coco_metadata() -> dict[str, object]:
    metadata: dict[str, object] = json.loads((COCO_DETECTOR_DIR / METADATA_FILE).read_text())
    return metadata


def fake_detector_dir(folder: Path, payload: bytes = b"detector-onnx") -> Path:
    """A detector folder with stand-in model bytes (the registry only copies files)."""
    folder.mkdir(parents=True, exist_ok=True)
    (folder / MODEL_FILE).write_bytes(payload)
    (folder / METADATA_FILE).write_text(json.dumps(coco_metadata()))
    (folder / "LICENSE").write_text("a licence\n")
    return folder


def never_detecting_dir(folder: Path) -> Path:
    """A real detector of the contract's shape that finds nothing (every score 0): a
    deliberately bad active detector that needs no training."""
    from holiscene_schema.detector_model import INPUT_NAME, INPUT_SIZE, MAX_DETECTIONS, OUTPUT_NAME
    from onnx import TensorProto, checker, helper, save

    image = helper.make_tensor_value_info(
        INPUT_NAME, TensorProto.FLOAT, [1, INPUT_SIZE, INPUT_SIZE, 3]
    )
    rows = helper.make_tensor_value_info(OUTPUT_NAME, TensorProto.FLOAT, [1, MAX_DETECTIONS, 6])
    nodes = [
        helper.make_node("ReduceSum", [INPUT_NAME], ["total"], keepdims=0),
        helper.make_node("Mul", ["total", "zero"], ["nothing"]),
        helper.make_node("Expand", ["nothing", "shape"], [OUTPUT_NAME]),
    ]
    graph = helper.make_graph(
        nodes,
        "never_detects",
        [image],
        [rows],
        initializer=[
            helper.make_tensor("zero", TensorProto.FLOAT, [], [0.0]),
            helper.make_tensor("shape", TensorProto.INT64, [3], [1, MAX_DETECTIONS, 6]),
        ],
    )
    model = helper.make_model(graph, opset_imports=[helper.make_opsetid("", 17)])
    model.ir_version = 8
    checker.check_model(model)
    folder.mkdir(parents=True, exist_ok=True)
    save(model, str(folder / MODEL_FILE))
    (folder / METADATA_FILE).write_text(json.dumps({**coco_metadata(), "name": "never detects"}))
    return folder


def copy_of_coco_detector(folder: Path) -> Path:
    shutil.copytree(COCO_DETECTOR_DIR, folder)
    return folder
