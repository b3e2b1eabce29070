"""TensorFlow.js graph model (model.json + weight shards) -> ONNX, for the ops our detector uses.

Build time only (it needs the `onnx` package of the train extra). tf2onnx's TensorFlow.js input
does not read the fused ops a TF.js graph model is saved with (`_FusedConv2D`,
`FusedDepthwiseConv2dNative`), so this writes the ONNX graph node by node with onnx's helper
API.

Layout: TF.js graphs are NHWC, ONNX convolutions NCHW. The input is transposed once; every 4D
activation then stays NCHW (constants broadcast along channels are reshaped to [C, 1, 1],
axes of Mean and ConcatV2 are remapped) until a node named in `nhwc_outputs` (the detection
heads), where it is transposed back; ops after those run on NHWC tensors as written.
"""

from __future__ import annotations

from collections.abc import Iterable
from dataclasses import dataclass, field
from typing import Any

import numpy as np
import onnx
from onnx import TensorProto, helper, numpy_helper

from .tfjs_graph import UnsupportedGraphError, attr, tensor_name, topological

_ONNX_OF_TF = {"DT_FLOAT": TensorProto.FLOAT, "DT_INT32": TensorProto.INT32}
_NCHW_AXIS = {0: 0, 1: 2, 2: 3, 3: 1, -1: 1}


@dataclass
class _Builder:
    weights: dict[str, np.ndarray]
    nhwc_outputs: frozenset[str]
    nodes: list[onnx.NodeProto] = field(default_factory=list)
    initializers: dict[str, onnx.TensorProto] = field(default_factory=dict)
    nchw: set[str] = field(default_factory=set)  # tensors held transposed to NCHW
    counter: int = 0

    def fresh(self, hint: str) -> str:
        self.counter += 1
        return f"{hint}__{self.counter}"

    def const(self, array: np.ndarray, hint: str) -> str:
        name = self.fresh(hint)
        self.initializers[name] = numpy_helper.from_array(array, name)
        return name

    def add(self, op: str, inputs: list[str], outputs: list[str], **attrs: Any) -> None:
        self.nodes.append(helper.make_node(op, inputs, outputs, **attrs))

    def relu6(self, source: str, out: str) -> None:
        zero = self.const(np.array(0, np.float32), "zero")
        self.add("Clip", [source, zero, self.const(np.array(6, np.float32), "six")], [out])

    def value(self, name: str) -> np.ndarray | None:
        """A constant's value, or None for a computed tensor."""
        return self.weights.get(name.split(":")[0]) if ":" not in name else None

    def operand(self, name: str, like: str | None) -> str:
        """A node input: constants become initializers, shaped to broadcast against `like`."""
        value = self.value(name)
        if value is None:
            return tensor_name(name)
        if like is not None and like in self.nchw and value.ndim == 1 and value.size > 1:
            value = value.reshape(-1, 1, 1)
        return self.const(value, name)


def _same_or_valid(node: dict[str, Any]) -> str:
    padding = attr(node, "padding")
    if padding == "SAME":
        return "SAME_UPPER"  # TF puts the odd pixel of SAME padding after, as SAME_UPPER does
    if padding == "VALID":
        return "VALID"
    raise UnsupportedGraphError(f"{node['name']}: padding {padding!r}")


def _check_nhwc(node: dict[str, Any]) -> None:
    layout = attr(node, "data_format")
    if layout not in (None, "NHWC"):
        raise UnsupportedGraphError(f"{node['name']}: data format {layout!r}")


def _conv(b: _Builder, node: dict[str, Any], depthwise: bool) -> None:
    _check_nhwc(node)
    name = node["name"]
    inputs = node["input"]
    source = tensor_name(inputs[0])
    if source not in b.nchw:
        raise UnsupportedGraphError(f"{name}: convolution of a tensor not in NCHW")
    kernel = b.value(inputs[1])
    if kernel is None:
        raise UnsupportedGraphError(f"{name}: computed convolution weights")
    strides = attr(node, "strides") or [1, 1, 1, 1]
    dilations = attr(node, "dilations") or [1, 1, 1, 1]
    if depthwise:  # H, W, C, M -> C * M, 1, H, W
        h, w, c, m = kernel.shape
        weight = kernel.transpose(2, 3, 0, 1).reshape(c * m, 1, h, w)
        group = c
    else:  # H, W, I, O -> O, I, H, W
        weight = kernel.transpose(3, 2, 0, 1)
        group = 1
    conv_inputs = [source, b.const(np.ascontiguousarray(weight, np.float32), f"{name}/W")]
    fused = attr(node, "fused_ops") or []
    if fused[:1] == ["BiasAdd"]:
        bias = b.value(inputs[2])
        if bias is None:
            raise UnsupportedGraphError(f"{name}: computed bias")
        conv_inputs.append(b.const(bias.astype(np.float32), f"{name}/B"))
        fused = fused[1:]
    elif fused:
        raise UnsupportedGraphError(f"{name}: fused ops {fused}")
    activation = fused[0] if fused else None
    if len(fused) > 1 or activation not in (None, "Relu", "Relu6"):
        raise UnsupportedGraphError(f"{name}: fused ops {attr(node, 'fused_ops')}")
    out = name if activation is None else b.fresh(name)
    b.add(
        "Conv",
        conv_inputs,
        [out],
        auto_pad=_same_or_valid(node),
        strides=strides[1:3],
        dilations=dilations[1:3],
        group=group,
        kernel_shape=list(kernel.shape[:2]),
    )
    if activation == "Relu":
        b.add("Relu", [out], [name])
    elif activation == "Relu6":
        b.add(
            "Clip",
            [
                out,
                b.const(np.array(0, np.float32), "zero"),
                b.const(np.array(6, np.float32), "six"),
            ],
            [name],
        )
    b.nchw.add(name)


def _elementwise(b: _Builder, node: dict[str, Any], op: str) -> None:
    inputs = node["input"]
    computed = [tensor_name(i) for i in inputs if b.value(i) is None]
    like = next((t for t in computed if t in b.nchw), computed[0] if computed else None)
    b.add(op, [b.operand(i, like) for i in inputs], [node["name"]])
    if any(t in b.nchw for t in computed):
        b.nchw.add(node["name"])


def _unary(b: _Builder, node: dict[str, Any], op: str, **attrs: Any) -> None:
    source = tensor_name(node["input"][0])
    name = node["name"]
    if op == "Clip":
        b.relu6(source, name)
    else:
        b.add(op, [source], [name], **attrs)
    if source in b.nchw:
        b.nchw.add(name)


def _constant_int(b: _Builder, node: dict[str, Any], index: int) -> np.ndarray:
    value = b.value(node["input"][index])
    if value is None:
        raise UnsupportedGraphError(f"{node['name']}: computed argument {index}")
    return value.astype(np.int64)


def _mean(b: _Builder, node: dict[str, Any]) -> None:
    source = tensor_name(node["input"][0])
    axes = [int(a) for a in np.atleast_1d(_constant_int(b, node, 1))]
    if source in b.nchw:
        axes = [_NCHW_AXIS[a] for a in axes]
    keep = 1 if attr(node, "keep_dims") else 0
    # ReduceMean takes its axes as an input from opset 18; this graph targets opset 17.
    b.add("ReduceMean", [source], [node["name"]], axes=axes, keepdims=keep)
    if source in b.nchw and keep:
        b.nchw.add(node["name"])


def _concat(b: _Builder, node: dict[str, Any]) -> None:
    count = attr(node, "N") or len(node["input"]) - 1
    parts = node["input"][:count]
    axis = int(_constant_int(b, node, count))
    layouts = {tensor_name(p) in b.nchw for p in parts if b.value(p) is None}
    if layouts == {True}:
        axis = _NCHW_AXIS[axis]
        b.nchw.add(node["name"])
    elif len(layouts) > 1:
        raise UnsupportedGraphError(f"{node['name']}: concatenation of mixed layouts")
    b.add("Concat", [b.operand(p, None) for p in parts], [node["name"]], axis=axis)


def _resize_bilinear(b: _Builder, node: dict[str, Any]) -> None:
    source = tensor_name(node["input"][0])
    if source not in b.nchw:
        raise UnsupportedGraphError(f"{node['name']}: resize of a tensor not in NCHW")
    size = _constant_int(b, node, 1)
    if attr(node, "align_corners"):
        mode = "align_corners"
    elif attr(node, "half_pixel_centers"):
        mode = "half_pixel"
    else:
        mode = "asymmetric"
    shape_of = b.fresh(f"{node['name']}/shape")
    batch_channels = b.fresh(f"{node['name']}/nc")
    sizes = b.fresh(f"{node['name']}/sizes")
    b.add("Shape", [source], [shape_of])
    b.add(
        "Slice",
        [
            shape_of,
            b.const(np.array([0], np.int64), "s0"),
            b.const(np.array([2], np.int64), "s2"),
        ],
        [batch_channels],
    )
    b.add("Concat", [batch_channels, b.const(size, "hw")], [sizes], axis=0)
    b.add(
        "Resize",
        [source, "", "", sizes],
        [node["name"]],
        mode="linear",
        coordinate_transformation_mode=mode,
    )
    b.nchw.add(node["name"])


def _max_pool(b: _Builder, node: dict[str, Any]) -> None:
    _check_nhwc(node)
    source = tensor_name(node["input"][0])
    ksize = attr(node, "ksize")
    strides = attr(node, "strides")
    transposed = source not in b.nchw
    pooled_in = source
    if transposed:
        pooled_in = b.fresh(f"{node['name']}/nchw")
        b.add("Transpose", [source], [pooled_in], perm=[0, 3, 1, 2])
    pooled = b.fresh(node["name"]) if transposed else node["name"]
    b.add(
        "MaxPool",
        [pooled_in],
        [pooled],
        kernel_shape=ksize[1:3],
        strides=strides[1:3],
        auto_pad=_same_or_valid(node),
    )
    if transposed:
        b.add("Transpose", [pooled], [node["name"]], perm=[0, 2, 3, 1])
    else:
        b.nchw.add(node["name"])


def _strided_slice(b: _Builder, node: dict[str, Any]) -> None:
    source = tensor_name(node["input"][0])
    if source in b.nchw:
        raise UnsupportedGraphError(f"{node['name']}: strided slice of an NCHW tensor")
    begin, end, step = (_constant_int(b, node, i) for i in (1, 2, 3))
    for mask in ("ellipsis_mask", "new_axis_mask", "shrink_axis_mask"):
        if attr(node, mask):
            raise UnsupportedGraphError(f"{node['name']}: {mask} is not supported")
    begin_mask = attr(node, "begin_mask") or 0
    end_mask = attr(node, "end_mask") or 0
    big = np.iinfo(np.int64).max
    starts, ends = [], []
    for axis in range(len(begin)):
        forward = step[axis] > 0
        starts.append((0 if forward else big) if begin_mask >> axis & 1 else begin[axis])
        ends.append((big if forward else -big) if end_mask >> axis & 1 else end[axis])
    b.add(
        "Slice",
        [
            source,
            b.const(np.array(starts, np.int64), "starts"),
            b.const(np.array(ends, np.int64), "ends"),
            b.const(np.arange(len(begin), dtype=np.int64), "axes"),
            b.const(step.astype(np.int64), "steps"),
        ],
        [node["name"]],
    )


def _to_nhwc(b: _Builder, name: str) -> None:
    """Rename the NCHW tensor `name` and give `name` its NHWC transpose."""
    held = b.fresh(f"{name}/nchw")
    for onnx_node in b.nodes:
        onnx_node.output[:] = [held if o == name else o for o in onnx_node.output]
        onnx_node.input[:] = [held if i == name else i for i in onnx_node.input]
    b.add("Transpose", [held], [name], perm=[0, 2, 3, 1])
    b.nchw.discard(name)


def _convert_node(b: _Builder, node: dict[str, Any]) -> None:
    op = node["op"]
    name = node["name"]
    inputs = node.get("input", [])
    if op in ("_FusedConv2D", "Conv2D"):
        _conv(b, node, depthwise=False)
    elif op in ("FusedDepthwiseConv2dNative", "DepthwiseConv2dNative"):
        _conv(b, node, depthwise=True)
    elif op in ("Add", "AddV2", "Mul", "Sub", "Equal", "FloorMod", "FloorDiv"):
        onnx_op = {
            "AddV2": "Add",
            "FloorMod": "Mod",
            "FloorDiv": "Div",  # integer division of the non-negative indices this graph has
        }.get(op, op)
        _elementwise(b, node, onnx_op)
    elif op == "Relu6":
        _unary(b, node, "Clip")
    elif op in ("Relu", "Sigmoid", "Identity"):
        _unary(b, node, op)
    elif op == "Cast":
        dst = attr(node, "DstT")
        if dst not in _ONNX_OF_TF:
            raise UnsupportedGraphError(f"{name}: cast to {dst}")
        _unary(b, node, "Cast", to=_ONNX_OF_TF[dst])
    elif op == "Mean":
        _mean(b, node)
    elif op == "ConcatV2":
        _concat(b, node)
    elif op == "ResizeBilinear":
        _resize_bilinear(b, node)
    elif op == "MaxPool":
        _max_pool(b, node)
    elif op == "Reshape":
        source = tensor_name(inputs[0])
        if source in b.nchw:
            raise UnsupportedGraphError(f"{name}: reshape of an NCHW tensor")
        b.add("Reshape", [source, b.const(_constant_int(b, node, 1), "shape")], [name])
    elif op == "ExpandDims":
        axis = np.atleast_1d(_constant_int(b, node, 1))
        b.add("Unsqueeze", [tensor_name(inputs[0]), b.const(axis, "axes")], [name])
    elif op == "TopKV2":
        k = np.atleast_1d(_constant_int(b, node, 1))
        indices64 = b.fresh(f"{name}/indices")
        b.add(
            "TopK",
            [tensor_name(inputs[0]), b.const(k, "k")],
            [name, indices64],
            largest=1,
            sorted=1,
        )
        b.add("Cast", [indices64], [f"{name}:1"], to=TensorProto.INT32)
    elif op == "GatherV2":
        gather_axis = int(_constant_int(b, node, 2))
        b.add("Gather", [tensor_name(inputs[0]), tensor_name(inputs[1])], [name], axis=gather_axis)
    elif op == "StridedSlice":
        _strided_slice(b, node)
    else:
        raise UnsupportedGraphError(f"{name}: op {op} is not supported")
    if name in b.nhwc_outputs and name in b.nchw:
        _to_nhwc(b, name)


def _input_of(node: dict[str, Any]) -> onnx.ValueInfoProto:
    dims = [int(d["size"]) for d in node["attr"]["shape"]["shape"]["dim"]]
    dtype = _ONNX_OF_TF[node["attr"]["dtype"]["type"]]
    return helper.make_tensor_value_info(node["name"], dtype, dims)


def convert(
    model_json: dict[str, Any],
    weights: dict[str, np.ndarray],
    outputs: dict[str, str],
    nhwc_outputs: Iterable[str] = (),
    input_name: str | None = None,
) -> onnx.ModelProto:
    """The graph model as ONNX. `outputs` maps graph tensor names to the ONNX output names;
    `nhwc_outputs` names the 4D tensors where the NCHW part of the graph ends."""
    nodes = model_json["modelTopology"]["node"]
    placeholders = [n for n in nodes if n["op"] == "Placeholder"]
    if len(placeholders) != 1:
        raise UnsupportedGraphError(f"expected one input, found {len(placeholders)}")
    graph_input = placeholders[0]
    b = _Builder(weights=weights, nhwc_outputs=frozenset(nhwc_outputs))
    # The NHWC input, transposed once for the convolutions.
    b.add("Transpose", [graph_input["name"] + "/nhwc"], [graph_input["name"]], perm=[0, 3, 1, 2])
    b.nchw.add(graph_input["name"])
    for node in topological(nodes):
        if node["op"] in ("Const", "Placeholder"):
            continue
        _convert_node(b, node)
    onnx_input = _input_of(graph_input)
    onnx_input.name = input_name or graph_input["name"]
    _rename_tensor(b, graph_input["name"] + "/nhwc", onnx_input.name)
    graph_outputs = []
    for tf_name, onnx_name in outputs.items():
        if tf_name in b.nchw:
            raise UnsupportedGraphError(f"output {tf_name} is NCHW: name it in nhwc_outputs")
        b.add("Identity", [tf_name], [onnx_name])
        graph_outputs.append(
            helper.make_tensor_value_info(
                onnx_name, TensorProto.FLOAT, _signature_dims(model_json, tf_name)
            )
        )
    graph = helper.make_graph(
        b.nodes, "converted", [onnx_input], graph_outputs, list(b.initializers.values())
    )
    model = helper.make_model(graph, opset_imports=[helper.make_opsetid("", 17)])
    model.ir_version = 8
    onnx.checker.check_model(model)
    return model


def _signature_dims(model_json: dict[str, Any], tf_name: str) -> list[int | str]:
    """An output's dimensions from the model's signature (a name where it has none)."""
    signature = model_json.get("signature", {}).get("outputs", {}).get(tf_name)
    if signature is None:
        raise UnsupportedGraphError(f"{tf_name} is not an output in the model's signature")
    dims = signature["tensorShape"]["dim"]
    return [int(d["size"]) if int(d["size"]) >= 0 else f"d{i}" for i, d in enumerate(dims)]


def _rename_tensor(b: _Builder, old: str, new: str) -> None:
    for onnx_node in b.nodes:
        onnx_node.input[:] = [new if i == old else i for i in onnx_node.input]
