"""The COCO detector's frozen part as a feature extractor (onnxruntime), and its box head's
weights, for fine-tuning an NYU-40 head on top (training only: needs the `onnx` package).

The converted COCO model keeps the TF.js tensor names, so the neck's output
(`tower_0/CenternetHead/mul`, 128 channels at a quarter of the input's size, NCHW), the
backbone's last features before the neck (`tower_0/extern1/...`, 480 channels at a 32nd: the
neck squeezes them to 128 channels for COCO's classes, so a head for other classes reads them
too) and the COCO class heatmap before its last transpose can be made graph outputs of a
sub-model.
"""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path

import numpy as np
import onnx
import onnxruntime as ort
from holiscene_schema.detector_model import COCO_CLASSES, INPUT_NAME, INPUT_SIZE
from onnx import TensorProto, helper, numpy_helper

FEATURES = "tower_0/CenternetHead/mul"
DEEP_FEATURES = "tower_0/extern1/hard_swish/mul_1"
DEEP_CHANNELS = 480
DEEP_STRIDE = 32
# The backbone's last features at a 16th of the input (88 channels), where its stride-32
# blocks begin: the input of the copy of those blocks that an NYU-40 head may fine-tune.
MID_FEATURES = "tower_0/MobilenetV3/expanded_conv_11/add"
MID_CHANNELS = 88
MID_STRIDE = 16
COCO_HEATMAP_NHWC = "tower_0/keypoints"
BOX_HEAD_DEPTHWISE = "tower_0/CenternetHead/centernet_wh_output/separable_conv2d/depthwise"
BOX_HEAD_POINTWISE = "tower_0/CenternetHead/centernet_wh_output/BiasAdd"
BOX_SCALE_NODE = "tower_0/mul"
FEATURE_CHANNELS = 128
COCO_CLASS_COUNT = len(COCO_CLASSES)


@dataclass(frozen=True)
class BoxHeadWeights:
    depthwise: np.ndarray  # (C, 1, 3, 3)
    pointwise: np.ndarray  # (4, C, 1, 1)
    bias: np.ndarray  # (4,)
    scale: float  # the head's output is multiplied by this


def _producer(model: onnx.ModelProto, output: str) -> onnx.NodeProto:
    for node in model.graph.node:
        if output in node.output:
            found: onnx.NodeProto = node
            return found
    raise ValueError(f"no node makes {output!r}: not the converted COCO detector")


def coco_heatmap_nchw(model: onnx.ModelProto) -> str:
    """The tensor the COCO heatmap is transposed from (the class probabilities in NCHW)."""
    return str(_producer(model, COCO_HEATMAP_NHWC).input[0])


def backbone_model(coco_model: Path, deep_input: str = DEEP_FEATURES) -> onnx.ModelProto:
    """The COCO model cut after its neck: images -> (features, COCO heatmap, the deep
    branch's input), NCHW, the first two [1, C, S / 4, S / 4], the last the deep features
    [1, 480, S / 32, S / 32] or, for a head that tunes its own copy of the last blocks
    (`deep_input=MID_FEATURES`), [1, 88, S / 16, S / 16]; with only the nodes they need."""
    model = onnx.load(str(coco_model))
    deep_shape = {
        DEEP_FEATURES: (DEEP_CHANNELS, DEEP_STRIDE),
        MID_FEATURES: (MID_CHANNELS, MID_STRIDE),
    }
    outputs = {
        FEATURES: (FEATURE_CHANNELS, 4),
        coco_heatmap_nchw(model): (COCO_CLASS_COUNT, 4),
        deep_input: deep_shape[deep_input],
    }
    needed: set[str] = set(outputs)
    kept: list[onnx.NodeProto] = []
    for node in reversed(model.graph.node):
        if needed.intersection(node.output):
            kept.append(node)
            needed.update(node.input)
    del model.graph.node[:]
    model.graph.node.extend(reversed(kept))
    del model.graph.output[:]
    model.graph.output.extend(
        helper.make_tensor_value_info(
            name, TensorProto.FLOAT, [1, channels, INPUT_SIZE // stride, INPUT_SIZE // stride]
        )
        for name, (channels, stride) in outputs.items()
    )
    initializers = [t for t in model.graph.initializer if t.name in needed]
    del model.graph.initializer[:]
    model.graph.initializer.extend(initializers)
    onnx.checker.check_model(model)
    return model


def box_head_weights(coco_model: Path) -> BoxHeadWeights:
    model = onnx.load(str(coco_model))
    init = {t.name: numpy_helper.to_array(t) for t in model.graph.initializer}
    depthwise = _producer(model, BOX_HEAD_DEPTHWISE)
    pointwise = _producer(model, BOX_HEAD_POINTWISE)
    scale = _producer(model, BOX_SCALE_NODE)
    return BoxHeadWeights(
        depthwise=init[depthwise.input[1]],
        pointwise=init[pointwise.input[1]],
        bias=init[pointwise.input[2]],
        scale=float(init[scale.input[1]]),
    )


class FeatureExtractor:
    """Runs the cut COCO model; `__call__` gives (features, COCO heatmap, the deep branch's
    input) for one input."""

    def __init__(self, coco_model: Path, threads: int = 2, deep_input: str = DEEP_FEATURES) -> None:
        options = ort.SessionOptions()
        options.intra_op_num_threads = threads
        self.session = ort.InferenceSession(
            backbone_model(coco_model, deep_input).SerializeToString(),
            options,
            providers=["CPUExecutionProvider"],
        )
        self.outputs = [o.name for o in self.session.get_outputs()]

    def __call__(self, tensor: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        features, heatmap, deep = self.session.run(self.outputs, {INPUT_NAME: tensor})
        return np.asarray(features), np.asarray(heatmap), np.asarray(deep)
