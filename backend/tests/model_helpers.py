"""Helpers for the model registry and retraining tests: labelled scenes and model folders."""

from __future__ import annotations

import json
from functools import cache
from pathlib import Path

import cv2
from holiscene.inputs import InputFiles, load_photo
from holiscene.store.scenes import SceneStore
from holiscene.synth.generate import synthesize
from holiscene_schema import Scene

# Seeds of labelled scenes the retraining tests store (no other test uses them). Each has 10
# or more labelled objects, on each an untrained network scores at most 0.3 and one trained
# for a few epochs at least 0.7: whatever the held-out split, trained beats untrained.
LABELLED_SEEDS = (4102, 4103, 4106, 4108, 4109, 4110)


@cache
def _synthetic(seed: int) -> tuple[bytes, Scene]:
    synthetic = synthesize(seed)
    ok, png = cv2.imencode(".png", cv2.cvtColor(synthetic.frame.rgb, cv2.COLOR_RGB2BGR))
    assert ok
    return png.tobytes(), synthetic.truth


def store_labelled_scene(scenes: SceneStore, seed: int) -> str:
    """A synthetic scene with its true supports (set by a person: source 'manual')."""
    png, truth = _synthetic(seed)
    photo = load_photo(png)
    summary = scenes.create(InputFiles(photo=photo, K=None, detections=None), truth, "test")
    return summary.id


def store_unlabelled_scene(scenes: SceneStore, seed: int) -> str:
    """The same scene with the supports marked as the pipeline's guesses ('auto')."""
    png, truth = _synthetic(seed)
    auto = [s.model_copy(update={"source": "auto"}) for s in truth.supports]
    scene = truth.model_copy(update={"supports": auto})
    photo = load_photo(png)
    return scenes.create(InputFiles(photo=photo, K=None, detections=None), scene, "test").id


def fake_model_dir(folder: Path, payload: bytes = b"onnx-bytes", curve: bool = True) -> Path:
    """A model folder with stand-in file contents: the registry stores files, it does not
    read the network (the retraining tests use real models)."""
    folder.mkdir(parents=True, exist_ok=True)
    (folder / "model.onnx").write_bytes(payload)
    (folder / "metrics.json").write_text(json.dumps({"validation_accuracy": 0.5}))
    (folder / "data.json").write_text(json.dumps({"labelled_scenes": []}))
    (folder / "priors.json").write_text("{}")
    if curve:
        (folder / "curve.png").write_bytes(b"\x89PNG\r\n\x1a\n-curve")
    return folder


def always_wrong_model_dir(folder: Path) -> Path:
    """A real ONNX model of the contract's shape whose every answer is "the object holds
    itself up" (never a label): a deliberately bad active model (accuracy 0) that needs no
    training."""
    from holiscene_schema.relation_model import INPUT_NAMES, OUTPUT_NAME
    from onnx import TensorProto, checker, helper, save

    inputs = [
        helper.make_tensor_value_info("image", TensorProto.FLOAT, [1, 3, "H", "W"]),
        helper.make_tensor_value_info("masks", TensorProto.FLOAT, ["N", "h", "w"]),
        helper.make_tensor_value_info("boxes", TensorProto.FLOAT, ["N", 4]),
        helper.make_tensor_value_info("classes", TensorProto.INT64, ["N"]),
    ]
    assert [i.name for i in inputs] == list(INPUT_NAMES)
    const = helper.make_tensor
    nodes = [
        helper.make_node("Shape", ["classes"], ["n"]),
        helper.make_node("Add", ["n", "three"], ["columns"]),
        helper.make_node("Concat", ["n", "columns"], ["square"], axis=0),
        helper.make_node(
            "ConstantOfShape", ["square"], ["zeros"], value=const("z", TensorProto.FLOAT, [1], [0])
        ),
        helper.make_node("EyeLike", ["zeros"], ["self_below"]),  # [i, i] = 1: i on itself
        helper.make_node("Unsqueeze", ["self_below", "last"], ["below"]),
        helper.make_node("Unsqueeze", ["zeros", "last"], ["behind"]),
        helper.make_node("Concat", ["below", "behind"], [OUTPUT_NAME], axis=2),
    ]
    graph = helper.make_graph(
        nodes,
        "always_wrong_support_model",
        inputs,
        [helper.make_tensor_value_info(OUTPUT_NAME, TensorProto.FLOAT, ["N", "M", 2])],
        initializer=[
            const("three", TensorProto.INT64, [1], [3]),
            const("last", TensorProto.INT64, [1], [2]),
        ],
    )
    model = helper.make_model(graph, opset_imports=[helper.make_opsetid("", 17)])
    model.ir_version = 8
    checker.check_model(model)
    folder.mkdir(parents=True, exist_ok=True)
    save(model, str(folder / "model.onnx"))
    (folder / "metrics.json").write_text(json.dumps({"note": "answers self-support"}))
    return folder
