"""The NYU-40 head's own copy of the backbone's stride-32 blocks: the graph's nodes run by
PyTorch give what onnxruntime gives, TensorFlow's SAME padding included; an operator the
runner does not know is refused by name; and a short training run that tunes the copy
exports one ONNX file that the runtime loads and that agrees with PyTorch, while the COCO
model's own blocks stay as they were."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import onnx
import onnxruntime as ort
import pytest
import torch
from holiscene.learning.detector.backbone import (
    DEEP_FEATURES,
    MID_FEATURES,
    MID_STRIDE,
    FeatureExtractor,
)
from holiscene.learning.detector.data import BoxedPhoto, synthetic_photos
from holiscene.learning.detector.net import deep_blocks
from holiscene.learning.detector.onnx_subgraph import OnnxSubgraph, UnsupportedGraphError
from holiscene.learning.detector.runtime import COCO_DETECTOR_DIR, MODEL_FILE, Detector, preprocess
from holiscene.learning.detector.train import DetectorTrainConfig, train_detector
from holiscene_schema.detector_model import INPUT_SIZE
from onnx import TensorProto, helper, numpy_helper

COCO_MODEL = COCO_DETECTOR_DIR / MODEL_FILE
SEEDS = range(931_000, 931_005)  # rooms no other training or benchmark uses


@pytest.fixture(scope="module")
def rooms(tmp_path_factory: pytest.TempPathFactory) -> list[BoxedPhoto]:
    return synthetic_photos(SEEDS, tmp_path_factory.mktemp("rooms"), workers=1)


def test_the_copy_gives_the_backbones_deep_features(rooms: list[BoxedPhoto]) -> None:
    tensor = preprocess(rooms[0].rgb)
    _, _, deep = FeatureExtractor(COCO_MODEL)(tensor)
    _, _, mid = FeatureExtractor(COCO_MODEL, deep_input=MID_FEATURES)(tensor)
    assert mid.shape == (1, 88, INPUT_SIZE // MID_STRIDE, INPUT_SIZE // MID_STRIDE)
    with torch.no_grad():
        copied = deep_blocks(COCO_MODEL)(torch.from_numpy(mid)).numpy()
    assert copied.shape == deep.shape
    assert np.abs(copied - deep).max() < 1e-4 * max(1.0, float(np.abs(deep).max()))


def _one_conv_model(auto_pad: str, stride: int, size: int) -> onnx.ModelProto:
    rng = np.random.default_rng(3)
    weight = rng.normal(size=(4, 2, 5, 5)).astype(np.float32)
    bias = rng.normal(size=4).astype(np.float32)
    scale = np.array(0.5, np.float32)
    nodes = [
        helper.make_node(
            "Conv", ["x", "w", "b"], ["c"], auto_pad=auto_pad, strides=[stride, stride],
            kernel_shape=[5, 5],
        ),
        helper.make_node("Mul", ["half", "c"], ["m"]),
        helper.make_node("ReduceMean", ["m"], ["y"], axes=[2, 3], keepdims=1),
    ]  # fmt: skip
    graph = helper.make_graph(
        nodes,
        "one conv",
        [helper.make_tensor_value_info("x", TensorProto.FLOAT, [1, 2, size, size])],
        [
            helper.make_tensor_value_info("m", TensorProto.FLOAT, None),
            helper.make_tensor_value_info("y", TensorProto.FLOAT, None),
        ],
        [
            numpy_helper.from_array(weight, "w"),
            numpy_helper.from_array(bias, "b"),
            numpy_helper.from_array(scale, "half"),
        ],
    )
    return helper.make_model(graph, opset_imports=[helper.make_opsetid("", 13)])


@pytest.mark.parametrize(
    ("auto_pad", "stride", "size"),
    [("SAME_UPPER", 2, 7), ("SAME_UPPER", 2, 8), ("SAME_LOWER", 2, 7), ("SAME_UPPER", 1, 6)],
)
def test_padding_and_constants_as_onnxruntime(auto_pad: str, stride: int, size: int) -> None:
    model = _one_conv_model(auto_pad, stride, size)
    x = np.random.default_rng(4).normal(size=(1, 2, size, size)).astype(np.float32)
    session = ort.InferenceSession(model.SerializeToString(), providers=["CPUExecutionProvider"])
    for name, expected in zip(["m", "y"], session.run(["m", "y"], {"x": x}), strict=True):
        with torch.no_grad():
            ours = OnnxSubgraph(model, "x", name)(torch.from_numpy(x)).numpy()
        assert ours.shape == expected.shape
        assert np.abs(ours - expected).max() < 1e-4
    # The Conv's weight and bias are parameters; the scalar is a constant.
    assert sorted(p.numel() for p in OnnxSubgraph(model, "x", "m").parameters()) == [4, 200]


def test_an_unknown_operator_is_refused_by_name() -> None:
    model = _one_conv_model("SAME_UPPER", 1, 6)
    model.graph.node.append(helper.make_node("Softmax", ["m"], ["s"]))
    with pytest.raises(UnsupportedGraphError, match="Softmax"):
        OnnxSubgraph(model, "x", "s")
    with pytest.raises(UnsupportedGraphError, match="does not depend"):
        OnnxSubgraph(model, "m", "x")


def test_training_with_tuned_blocks_exports_one_faithful_model(
    tmp_path: Path, rooms: list[BoxedPhoto]
) -> None:
    out = tmp_path / "tuned"
    config = DetectorTrainConfig(epochs=1, batch=2, views=1, tune_deep_blocks=True)
    before = onnx.load(str(COCO_MODEL)).SerializeToString()
    metrics = train_detector(rooms[:3], rooms[3:], config, out)
    assert metrics["export_difference"] < 1e-3
    assert "stride-32 blocks" in (out / "metadata.json").read_text()
    # The copy was trained: its weights left the COCO model's.
    state = torch.load(out / "head.pt")["state"]
    tuned = [v for k, v in state.items() if k.startswith("deep_blocks.")]
    original = [p.detach() for p in deep_blocks(COCO_MODEL).parameters()]
    assert len(tuned) == len(original) > 0
    assert any(not torch.equal(t, o) for t, o in zip(tuned, original, strict=True))
    assert onnx.load(str(COCO_MODEL)).SerializeToString() == before
    # One file of the contract: the runtime reads it, and the frozen deep features still
    # feed the COCO neck inside it (the graph keeps both).
    detector = Detector(out)
    assert detector.raw(preprocess(rooms[4].rgb)).shape == (1, 100, 6)
    graph_outputs = {o for node in onnx.load(str(out / MODEL_FILE)).graph.node for o in node.output}
    assert DEEP_FEATURES in graph_outputs
