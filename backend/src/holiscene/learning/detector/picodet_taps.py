"""PicoDet's evidence per anchor, tapped from the wrapped graph, for a head of other classes.

PicoDet (a GFL detector; `picodet_contract.py`) scores each of its 3598 anchors (a 52, 26, 13
and 7 cell grid over the 416-pixel input) from one 96-channel feature map per level: a class
convolution gives COCO's 80 logits, a second branch an alignment probability, and the score is
the square root of their product. Its box regression is class-free: on the 17 real photos some
anchor's box meets 98.6% of the given boxes at IoU 0.5 (91.8% at 0.7), so what COCO lacks is
the classes, not the boxes. This module finds, by the graph's structure, each level's feature
map and where its class branch begins, its alignment probability, the COCO scores and the
decoded boxes that feed the NMS, and runs the wrapped model up to them (onnxruntime; training
only, it needs the `onnx` package).
"""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path

import numpy as np
import onnx
import onnxruntime as ort
from holiscene_schema.detector_model import INPUT_NAME, INPUT_SIZE
from onnx import TensorProto, helper, numpy_helper

from .picodet_contract import PICODET_SIZE, PicoDetGraphError, nms_inputs, upstream

STRIDES = (8, 16, 32, 64)  # in PicoDet's 416-pixel input, one per level
FEATURE_CHANNELS = 96


@dataclass(frozen=True)
class PicoDetTapNames:
    """The wrapped graph's tensors a new head reads."""

    features: tuple[str, ...]  # [1, 96, H, W] per level: what the class convolution reads
    # [1, 96, H, W] per level: where the level's class branch (the five convolutions and the
    # squeeze-and-excite that make `features`) begins
    branch_inputs: tuple[str, ...]
    alignment: tuple[str, ...]  # [1, 1, H, W] per level: the alignment probability
    coco_scores: str  # [1, 80, N]: COCO's scores, the NMS's input
    boxes: str  # [1, N, 4]: every anchor's box in the contract's 512-pixel input
    nms_settings: tuple[str, ...]  # the NMS's own settings (boxes per class, IoU, lowest score)


def tap_names(model: onnx.ModelProto) -> PicoDetTapNames:
    """Each level's class features and alignment, found as the inputs of the score's
    sigmoid(class conv(features)) x sigmoid(alignment), in graph (level) order."""
    producer = {name: node for node in model.graph.node for name in node.output}
    features: list[str] = []
    alignment: list[str] = []
    for node in model.graph.node:
        parents = [producer.get(name) for name in node.input]
        if node.op_type != "Mul" or not all(p and p.op_type == "Sigmoid" for p in parents):
            continue
        for sigmoid in parents:
            assert sigmoid is not None
            source = producer.get(sigmoid.input[0])
            if source is not None and source.op_type == "Conv":
                features.append(source.input[0])
            else:
                alignment.append(sigmoid.output[0])
    if len(features) != len(STRIDES) or len(alignment) != len(STRIDES):
        raise PicoDetGraphError(
            f"expected {len(STRIDES)} levels of class features and alignment, found "
            f"{len(features)} and {len(alignment)}"
        )
    inputs = nms_inputs(model.graph)
    branches = tuple(_branch_input(producer, f) for f in features)
    return PicoDetTapNames(
        tuple(features), branches, tuple(alignment), inputs[1], inputs[0], tuple(inputs[2:])
    )


BRANCH_CONVOLUTIONS = 5  # depthwise, pointwise, depthwise, pointwise, the 1x1 after the SE


def _branch_input(producer: dict[str, onnx.NodeProto], features: str) -> str:
    """Walking back from a level's class features along each node's first input, what the
    branch's fifth convolution reads."""
    tensor, convolutions = features, 0
    while convolutions < BRANCH_CONVOLUTIONS:
        node = producer.get(tensor)
        if node is None:
            raise PicoDetGraphError(f"the class branch of {features!r} is shorter than expected")
        convolutions += node.op_type == "Conv"
        tensor = node.input[0]
    return tensor


@dataclass(frozen=True)
class NmsSettings:
    """PicoDet's own NMS settings, as its graph holds them."""

    per_class: int  # boxes kept per class at most
    iou: float  # a box overlapping a kept one of its class more than this is dropped
    lowest_score: float


def nms_settings(model: onnx.ModelProto, names: PicoDetTapNames) -> NmsSettings:
    """The values of the graph's NMS settings (Constant nodes or initializers)."""
    values = {t.name: numpy_helper.to_array(t) for t in model.graph.initializer}
    for node in model.graph.node:
        if node.op_type == "Constant" and node.output[0] in names.nms_settings:
            values[node.output[0]] = numpy_helper.to_array(node.attribute[0].t)
    per_class, iou, lowest = (values[name].reshape(-1)[0] for name in names.nms_settings)
    return NmsSettings(int(per_class), float(iou), float(lowest))


def grid_sizes() -> list[int]:
    """Cells per side of each level (PicoDet rounds up)."""
    return [-(-PICODET_SIZE // stride) for stride in STRIDES]


def anchor_points() -> np.ndarray:
    """Every anchor's centre [N, 2] (x, y) in the contract's 512-pixel input, in the order the
    graph lists anchors (level, then row, then column)."""
    scale = INPUT_SIZE / PICODET_SIZE
    points = []
    for stride, cells in zip(STRIDES, grid_sizes(), strict=True):
        ys, xs = np.meshgrid(np.arange(cells), np.arange(cells), indexing="ij")
        centres = (np.stack([xs.ravel(), ys.ravel()], axis=1) + 0.5) * stride * scale
        points.append(centres)
    return np.concatenate(points).astype(np.float32)


@dataclass(frozen=True)
class TappedAnchors:
    branch_inputs: tuple[np.ndarray, ...]  # (96, H, W) per level
    alignment: np.ndarray  # (N,) probability
    coco_scores: np.ndarray  # (80, N)
    boxes: np.ndarray  # (N, 4) x1, y1, x2, y2 in the 512-pixel input


def tapped_model(model: onnx.ModelProto, names: PicoDetTapNames) -> onnx.ModelProto:
    """The wrapped model cut after the tapped tensors, which become its outputs."""
    outputs = [*names.branch_inputs, *names.alignment, names.coco_scores, names.boxes]
    graph = model.graph
    body = upstream(graph, set(outputs))
    used = {name for node in body for name in node.input}
    cut = helper.make_graph(
        body,
        "picodet_taps",
        list(graph.input),
        [helper.make_tensor_value_info(name, TensorProto.FLOAT, None) for name in outputs],
        initializer=[t for t in graph.initializer if t.name in used],
    )
    return helper.make_model(cut, opset_imports=model.opset_import, ir_version=model.ir_version)


class PicoDetTaps:
    """Runs the wrapped PicoDet up to its taps for one contract input [1, 512, 512, 3]."""

    def __init__(self, model_path: Path, threads: int = 2) -> None:
        self.model = onnx.load(str(model_path))
        self.names = tap_names(self.model)
        self.nms = nms_settings(self.model, self.names)
        options = ort.SessionOptions()
        options.intra_op_num_threads = threads
        self.session = ort.InferenceSession(
            tapped_model(self.model, self.names).SerializeToString(),
            options,
            providers=["CPUExecutionProvider"],
        )

    def __call__(self, tensor: np.ndarray) -> TappedAnchors:
        levels = len(STRIDES)
        out = self.session.run(None, {INPUT_NAME: tensor})
        alignment = np.concatenate([np.asarray(a).reshape(-1) for a in out[levels : 2 * levels]])
        return TappedAnchors(
            branch_inputs=tuple(np.asarray(f)[0] for f in out[:levels]),
            alignment=alignment,
            coco_scores=np.asarray(out[2 * levels])[0],
            boxes=np.asarray(out[2 * levels + 1])[0],
        )
