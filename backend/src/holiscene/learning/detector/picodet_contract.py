"""PicoDet (PaddleDetection's GFL detector, as converted to ONNX) put behind the detector contract.

The converted graph takes `image` [1, 3, 416, 416] (RGB scaled to [0, 1], ImageNet mean and
std) and `scale_factor` [1, 2], and ends in Paddle's multi-class NMS, which ONNX has no single
op for. The contract (holiscene_schema.detector_model) wants `images` [1, 512, 512, 3] RGB 0-255
and `detections` [1, 100, 6]. So, with the onnx helper API:

- in front: NHWC -> NCHW, bilinear resize 512 -> 416 (half-pixel centres), the normalisation;
- `scale_factor` becomes the constant 416 / 512, so boxes come out in the 512-pixel input;
- behind, in place of what followed the graph's NonMaxSuppression: the same per-class NMS
  with the model's own settings, then the MAX_DETECTIONS best of its rows (padded with
  score-0 rows when fewer survive) as x1, y1, x2, y2, score, class.

PicoDet is the one detector with NMS inside: its anchors, unlike CenterNet's peaks, repeat
each object many times. Decoding still does the contract's NMS per NYU-40 class on top.
"""

from __future__ import annotations

import numpy as np
import onnx
from holiscene_schema.detector_model import (
    INPUT_NAME,
    INPUT_SIZE,
    MAX_DETECTIONS,
    OPSET,
    OUTPUT_NAME,
)
from onnx import TensorProto, helper, numpy_helper

PICODET_INPUT = "image"
PICODET_SCALE_INPUT = "scale_factor"
PICODET_SIZE = 416
IMAGENET_MEAN = (0.485, 0.456, 0.406)
IMAGENET_STD = (0.229, 0.224, 0.225)


class PicoDetGraphError(ValueError):
    """The converted graph is not the PicoDet this wrapper expects."""


def nms_inputs(graph: onnx.GraphProto) -> list[str]:
    """What the graph's one NonMaxSuppression reads: boxes [1, N, 4], scores [1, C, N], and
    the model's own settings (boxes kept per class, IoU, lowest score)."""
    nms = [node for node in graph.node if node.op_type == "NonMaxSuppression"]
    if len(nms) != 1 or len(nms[0].input) != 5:
        raise PicoDetGraphError(
            f"expected one NonMaxSuppression node with 5 inputs, found {len(nms)}"
        )
    return list(nms[0].input)


def _prefix_nodes() -> tuple[list[onnx.NodeProto], list[onnx.TensorProto]]:
    """Contract input -> PicoDet's normalised NCHW input."""
    size = np.array([1, 3, PICODET_SIZE, PICODET_SIZE], dtype=np.int64)
    mean = np.array(IMAGENET_MEAN, dtype=np.float32).reshape(1, 3, 1, 1) * 255.0
    std = np.array(IMAGENET_STD, dtype=np.float32).reshape(1, 3, 1, 1) * 255.0
    constants = [
        numpy_helper.from_array(size, "contract.resize_size"),
        numpy_helper.from_array(mean.astype(np.float32), "contract.mean_255"),
        numpy_helper.from_array(std.astype(np.float32), "contract.std_255"),
    ]
    nodes = [
        helper.make_node("Transpose", [INPUT_NAME], ["contract.nchw"], perm=[0, 3, 1, 2]),
        helper.make_node(
            "Resize",
            ["contract.nchw", "", "", "contract.resize_size"],
            ["contract.resized"],
            mode="linear",
            coordinate_transformation_mode="half_pixel",
        ),
        helper.make_node("Sub", ["contract.resized", "contract.mean_255"], ["contract.centred"]),
        helper.make_node("Div", ["contract.centred", "contract.std_255"], [PICODET_INPUT]),
    ]
    return nodes, constants


def suffix_nodes(nms_inputs: list[str]) -> tuple[list[onnx.NodeProto], list[onnx.TensorProto]]:
    """The model's NMS, then its MAX_DETECTIONS best rows as the contract's [1, k, 6]."""
    boxes, scores = nms_inputs[:2]
    k = MAX_DETECTIONS
    constants = [
        numpy_helper.from_array(np.array([k], np.int64), "contract.k"),
        numpy_helper.from_array(np.array([0], np.int64), "contract.axis0"),
        numpy_helper.from_array(np.array([1], np.int64), "contract.one"),
        numpy_helper.from_array(np.array([2], np.int64), "contract.two"),
        numpy_helper.from_array(np.array([3], np.int64), "contract.three"),
        numpy_helper.from_array(np.array([1], np.int64), "contract.step"),
        numpy_helper.from_array(np.zeros((k, 6), np.float32), "contract.padding_rows"),
        numpy_helper.from_array(np.zeros((k,), np.float32), "contract.padding_scores"),
    ]
    nodes = [
        # The model's own per-class NMS with its own settings, as PicoDet is meant to be
        # read: without it the best anchors are mostly copies of the same few objects.
        helper.make_node("NonMaxSuppression", nms_inputs, ["contract.selected"]),
        helper.make_node("GatherND", [scores, "contract.selected"], ["contract.kept_score"]),
        helper.make_node(
            "Slice",
            ["contract.selected", "contract.one", "contract.two", "contract.one", "contract.step"],
            ["contract.kept_class_int"],
        ),
        helper.make_node(
            "Slice",
            [
                "contract.selected",
                "contract.two",
                "contract.three",
                "contract.one",
                "contract.step",
            ],
            ["contract.kept_anchor_col"],
        ),
        helper.make_node(
            "Squeeze", ["contract.kept_anchor_col", "contract.one"], ["contract.kept_anchor"]
        ),
        helper.make_node("Squeeze", [boxes, "contract.axis0"], ["contract.boxes_n4"]),
        helper.make_node(
            "Gather", ["contract.boxes_n4", "contract.kept_anchor"], ["contract.kept_boxes"], axis=0
        ),
        helper.make_node(
            "Cast", ["contract.kept_class_int"], ["contract.kept_class"], to=TensorProto.FLOAT
        ),
        helper.make_node(
            "Unsqueeze", ["contract.kept_score", "contract.one"], ["contract.kept_score_col"]
        ),
        helper.make_node(
            "Concat",
            ["contract.kept_boxes", "contract.kept_score_col", "contract.kept_class"],
            ["contract.kept_rows"],
            axis=1,
        ),
        # Fewer than k survivors: rows of score 0 fill the output (decoding drops them).
        helper.make_node(
            "Concat", ["contract.kept_rows", "contract.padding_rows"], ["contract.rows"], axis=0
        ),
        helper.make_node(
            "Concat",
            ["contract.kept_score", "contract.padding_scores"],
            ["contract.scores"],
            axis=0,
        ),
        helper.make_node(
            "TopK",
            ["contract.scores", "contract.k"],
            ["contract.top_score", "contract.top_row"],
            axis=0,
        ),
        helper.make_node(
            "Gather", ["contract.rows", "contract.top_row"], ["contract.top_rows"], axis=0
        ),
        helper.make_node("Unsqueeze", ["contract.top_rows", "contract.axis0"], [OUTPUT_NAME]),
    ]
    return nodes, constants


def upstream(graph: onnx.GraphProto, outputs: set[str]) -> list[onnx.NodeProto]:
    """The nodes the given tensors depend on, in the graph's order."""
    producer = {name: node for node in graph.node for name in node.output}
    needed: set[int] = set()
    stack = list(outputs)
    while stack:
        node = producer.get(stack.pop())
        if node is None or id(node) in needed:
            continue
        needed.add(id(node))
        stack.extend(name for name in node.input if name)
    return [node for node in graph.node if id(node) in needed]


def _contract_input() -> onnx.ValueInfoProto:
    return helper.make_tensor_value_info(
        INPUT_NAME, TensorProto.FLOAT, [1, INPUT_SIZE, INPUT_SIZE, 3]
    )


def input_model() -> onnx.ModelProto:
    """The wrapper's front alone: contract input -> PicoDet's normalised input, for feeding
    the original model exactly what the wrapped one sees."""
    prefix, constants = _prefix_nodes()
    graph = helper.make_graph(
        prefix,
        "picodet_input",
        [_contract_input()],
        [
            helper.make_tensor_value_info(
                PICODET_INPUT, TensorProto.FLOAT, [1, 3, PICODET_SIZE, PICODET_SIZE]
            )
        ],
        initializer=constants,
    )
    return helper.make_model(graph, opset_imports=[helper.make_opsetid("", OPSET)], ir_version=8)


def wrap_picodet(converted: onnx.ModelProto, doc_string: str = "") -> onnx.ModelProto:
    """The converted PicoDet graph with the contract's input and output."""
    graph = converted.graph
    if [i.name for i in graph.input] != [PICODET_INPUT, PICODET_SCALE_INPUT]:
        raise PicoDetGraphError(
            f"expected inputs {PICODET_INPUT!r} and {PICODET_SCALE_INPUT!r}, "
            f"found {[i.name for i in graph.input]}"
        )
    nms_tensors = nms_inputs(graph)
    body = upstream(graph, set(nms_tensors))
    used = {name for node in body for name in node.input}
    initializers = [t for t in graph.initializer if t.name in used]
    # Boxes are divided by scale_factor (resized input -> photo); 416/512 maps them to the
    # contract's 512-pixel input instead.
    scale = numpy_helper.from_array(
        np.full((1, 2), PICODET_SIZE / INPUT_SIZE, np.float32), PICODET_SCALE_INPUT
    )
    prefix, prefix_constants = _prefix_nodes()
    suffix, suffix_constants = suffix_nodes(nms_tensors)
    wrapped_graph = helper.make_graph(
        prefix + body + suffix,
        "picodet_detector_contract",
        [_contract_input()],
        [helper.make_tensor_value_info(OUTPUT_NAME, TensorProto.FLOAT, [1, MAX_DETECTIONS, 6])],
        initializer=[*initializers, scale, *prefix_constants, *suffix_constants],
    )
    opset = max(OPSET, *(o.version for o in converted.opset_import if o.domain in ("", "ai.onnx")))
    model = helper.make_model(
        wrapped_graph,
        opset_imports=[helper.make_opsetid("", opset)],
        producer_name="holiscene",
        doc_string=doc_string,
    )
    model.ir_version = min(model.ir_version, 8)
    onnx.checker.check_model(model, full_check=True)
    return model
