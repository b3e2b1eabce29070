"""A stretch of an ONNX graph run by PyTorch, its weights trainable (training only).

The NYU-40 heads fine-tune copies of a converted graph's blocks (the CenterNet backbone's last
blocks, PicoDet's class branches; docs/detector.md). The converted graph is the only source of
those blocks, so rather than rewrite MobileNetV3 or PicoDet by hand, this module runs the
graph's own nodes between one tensor and another with PyTorch operators: convolutions and
batch norms' scales and shifts become parameters (their running statistics stay fixed), scalar
constants stay constants. Weights may be initializers or Constant nodes. Only the operators
those blocks use are known; any other is refused by name.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import onnx
import torch
import torch.nn.functional as F
from onnx import numpy_helper
from torch import nn


class UnsupportedGraphError(ValueError):
    """The stretch holds an operator or attribute this module does not run."""


@dataclass(frozen=True)
class _Step:
    op: str
    inputs: tuple[str, ...]
    output: str
    attributes: dict[str, object]


def _stretch(model: onnx.ModelProto, start: str, end: str) -> list[onnx.NodeProto]:
    """The nodes that `end` needs and that depend on `start`, in graph order."""
    downstream, after_start = {start}, []
    for node in model.graph.node:
        if downstream.intersection(node.input):
            downstream.update(node.output)
            after_start.append(node)
    if end not in downstream:
        raise UnsupportedGraphError(f"{end!r} does not depend on {start!r}")
    needed, kept = {end}, []
    for node in reversed(after_start):
        if needed.intersection(node.output):
            kept.append(node)
            needed.update(node.input)
    return list(reversed(kept))


class OnnxSubgraph(nn.Module):
    """Runs the nodes from tensor `start` to tensor `end` of `model`; every Conv's weight
    and bias become parameters (copies: the model is left as it is)."""

    SUPPORTED = frozenset({
        "Conv", "Mul", "Add", "Clip", "Relu", "Sigmoid", "ReduceMean", "BatchNormalization",
        "HardSwish", "GlobalAveragePool",
    })  # fmt: skip

    def __init__(self, model: onnx.ModelProto, start: str, end: str) -> None:
        super().__init__()
        self.start, self.end = start, end
        initializers = {t.name: numpy_helper.to_array(t) for t in model.graph.initializer}
        for node in model.graph.node:
            if node.op_type == "Constant" and node.attribute and node.attribute[0].name == "value":
                initializers[node.output[0]] = numpy_helper.to_array(node.attribute[0].t)
        self.weights = nn.ParameterDict()
        self.statistics: dict[str, str] = {}  # batch norms' running mean and variance: buffers
        self.constants: dict[str, float] = {}
        self._parameter_key: dict[str, str] = {}
        self.steps: list[_Step] = []
        for node in _stretch(model, start, end):
            if node.op_type not in self.SUPPORTED:
                raise UnsupportedGraphError(f"operator {node.op_type} ({node.name}) is not run")
            for position, name in enumerate(node.input):
                if name not in initializers:
                    continue
                value = initializers[name]
                if node.op_type == "BatchNormalization" and position >= 3:
                    if name not in self.statistics:
                        key = f"s{len(self.statistics)}"
                        self.statistics[name] = key
                        self.register_buffer(key, torch.from_numpy(value.copy()))
                elif value.size == 1 and node.op_type not in ("Conv", "BatchNormalization"):
                    self.constants[name] = float(value.reshape(()))
                elif name not in self._parameter_key:
                    key = f"p{len(self._parameter_key)}"  # ParameterDict keys cannot hold "/"
                    self._parameter_key[name] = key
                    self.weights[key] = nn.Parameter(torch.from_numpy(value.copy()))
            attributes = {a.name: onnx.helper.get_attribute_value(a) for a in node.attribute}
            self.steps.append(_Step(node.op_type, tuple(node.input), node.output[0], attributes))

    def _value(self, name: str, values: dict[str, torch.Tensor]) -> torch.Tensor | float:
        if name in values:
            return values[name]
        if name in self.constants:
            return self.constants[name]
        if name in self.statistics:
            statistic: torch.Tensor = getattr(self, self.statistics[name])
            return statistic
        weight: torch.Tensor = self.weights[self._parameter_key[name]]
        return weight

    def forward(self, x: torch.Tensor) -> torch.Tensor:
        values = {self.start: x}
        for step in self.steps:
            args = [self._value(name, values) for name in step.inputs if name]
            values[step.output] = _run(step, args)
        return values[self.end]


def _run(step: _Step, args: list[torch.Tensor | float]) -> torch.Tensor:
    if step.op == "Conv":
        return _conv(step, args)
    if step.op in ("Mul", "Add"):
        a, b = args
        result = a * b if step.op == "Mul" else a + b
        assert isinstance(result, torch.Tensor)
        return result
    x = args[0]
    assert isinstance(x, torch.Tensor)
    if step.op == "Clip":
        low, high = (float(v) for v in args[1:3])
        return torch.clamp(x, low, high)
    if step.op == "Relu":
        return F.relu(x)
    if step.op == "Sigmoid":
        return torch.sigmoid(x)
    if step.op == "HardSwish":
        return F.hardswish(x)
    if step.op == "GlobalAveragePool":
        return x.mean(dim=[2, 3], keepdim=True)
    if step.op == "BatchNormalization":
        scale, shift, mean, variance = args[1:5]
        assert all(isinstance(v, torch.Tensor) for v in (scale, shift, mean, variance))
        epsilon = float(step.attributes.get("epsilon", 1e-5))  # type: ignore[arg-type]
        return F.batch_norm(x, mean, variance, scale, shift, False, 0.0, epsilon)  # type: ignore[arg-type]
    axes = step.attributes.get("axes")
    if not isinstance(axes, list) or step.attributes.get("keepdims", 1) != 1:
        raise UnsupportedGraphError(f"ReduceMean with {step.attributes} is not run")
    return x.mean(dim=[int(a) for a in axes], keepdim=True)


def _conv(step: _Step, args: list[torch.Tensor | float]) -> torch.Tensor:
    x, weight, *rest = args
    assert isinstance(x, torch.Tensor) and isinstance(weight, torch.Tensor)
    bias = rest[0] if rest else None
    assert bias is None or isinstance(bias, torch.Tensor)
    attributes = step.attributes
    strides = [int(s) for s in attributes.get("strides", [1, 1])]  # type: ignore[attr-defined]
    dilations = [int(d) for d in attributes.get("dilations", [1, 1])]  # type: ignore[attr-defined]
    kernel = weight.shape[-2:]
    auto_pad = attributes.get("auto_pad", b"NOTSET")
    if auto_pad in (b"SAME_UPPER", b"SAME_LOWER"):
        # TensorFlow's SAME: output ceil(input / stride), the odd pixel of padding at the end
        # (SAME_UPPER) or the start.
        pads_begin, pads_end = [], []
        for size, stride, k, dilation in zip(x.shape[-2:], strides, kernel, dilations, strict=True):
            out = math.ceil(int(size) / stride)
            total = max((out - 1) * stride + (int(k) - 1) * dilation + 1 - int(size), 0)
            small, large = total // 2, total - total // 2
            upper = auto_pad == b"SAME_UPPER"
            pads_begin.append(small if upper else large)
            pads_end.append(large if upper else small)
    elif auto_pad in (b"NOTSET", b"VALID"):
        pads = [int(p) for p in attributes.get("pads", [0, 0, 0, 0])]  # type: ignore[attr-defined]
        pads_begin, pads_end = pads[:2], pads[2:]
    else:
        raise UnsupportedGraphError(f"Conv auto_pad {auto_pad!r} is not run")
    padded = F.pad(x, (pads_begin[1], pads_end[1], pads_begin[0], pads_end[0]))
    group = int(attributes.get("group", 1))  # type: ignore[call-overload]
    return F.conv2d(padded, weight, bias, stride=strides, dilation=dilations, groups=group)
