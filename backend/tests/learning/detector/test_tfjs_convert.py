"""The TF.js graph converter on a small graph of its own ops, against numpy's arithmetic."""

from __future__ import annotations

import base64
import json
from pathlib import Path
from typing import Any

import numpy as np
import onnxruntime as ort
import pytest
from holiscene.learning.detector.tfjs_convert import convert
from holiscene.learning.detector.tfjs_graph import (
    UnsupportedGraphError,
    load_graph_model,
    read_weights,
)


def _s(text: str) -> dict[str, str]:
    return {"s": base64.b64encode(text.encode()).decode()}


def _ints(*values: int) -> dict[str, Any]:
    return {"list": {"i": [str(v) for v in values]}}


def _node(name: str, op: str, inputs: list[str], **attrs: Any) -> dict[str, Any]:
    return {"name": name, "op": op, "input": inputs, "attr": attrs}


def _graph(
    tmp_path: Path, rng: np.random.Generator
) -> tuple[dict[str, Any], dict[str, np.ndarray]]:
    """images [1, 8, 8, 3] -> conv 3x3 stride 2 (+bias, Relu6) -> depthwise 3x3 -> x * mean
    over H, W -> resize to 8x8 -> concat with a 1x1 conv of the input -> sigmoid."""
    weights = {
        "conv/w": rng.normal(size=(3, 3, 3, 4)).astype(np.float32),
        "conv/b": rng.normal(size=4).astype(np.float32),
        "dw/w": rng.normal(size=(3, 3, 4, 1)).astype(np.float32),
        "axes": np.array([1, 2], np.int32),
        "size": np.array([8, 8], np.int32),
        "side/w": rng.normal(size=(1, 1, 3, 2)).astype(np.float32) * 0.01,
        "concat/axis": np.array(3, np.int32),
    }
    same, valid = _s("SAME"), _s("VALID")
    nodes = [
        {
            "name": "images",
            "op": "Placeholder",
            "attr": {
                "dtype": {"type": "DT_FLOAT"},
                "shape": {
                    "shape": {"dim": [{"size": "1"}, {"size": "8"}, {"size": "8"}, {"size": "3"}]}
                },
            },
        },
        *[{"name": k, "op": "Const", "attr": {}} for k in weights],
        _node(
            "conv",
            "_FusedConv2D",
            ["images", "conv/w", "conv/b"],
            padding=same,
            strides=_ints(1, 2, 2, 1),
            fused_ops={"list": {"s": [_s("BiasAdd")["s"], _s("Relu6")["s"]]}},
        ),
        _node(
            "dw", "DepthwiseConv2dNative", ["conv", "dw/w"], padding=same, strides=_ints(1, 1, 1, 1)
        ),
        _node("mean", "Mean", ["dw", "axes"], keep_dims={"b": True}),
        _node("scaled", "Mul", ["dw", "mean"]),
        _node(
            "up",
            "ResizeBilinear",
            ["scaled", "size"],
            align_corners={"b": False},
            half_pixel_centers={"b": False},
        ),
        _node("side", "Conv2D", ["images", "side/w"], padding=valid, strides=_ints(1, 1, 1, 1)),
        _node("cat", "ConcatV2", ["up", "side", "concat/axis"], N={"i": "2"}),
        _node("out", "Sigmoid", ["cat"]),
    ]
    # The weights as TF.js ships them: float16-quantised floats and plain int32, one shard.
    manifest, shard = [], b""
    for name, value in weights.items():
        if value.dtype == np.float32:
            shard += value.astype(np.float16).tobytes()
            quantised = {"dtype": "float16", "original_dtype": "float32"}
            manifest.append(
                {
                    "name": name,
                    "shape": list(value.shape),
                    "dtype": "float32",
                    "quantization": quantised,
                }
            )
        else:
            shard += value.tobytes()
            manifest.append({"name": name, "shape": list(value.shape), "dtype": "int32"})
    (tmp_path / "w.bin").write_bytes(shard)
    model_json = {
        "format": "graph-model",
        "modelTopology": {"node": nodes},
        "weightsManifest": [{"paths": ["w.bin"], "weights": manifest}],
        "signature": {
            "outputs": {
                "out": {
                    "tensorShape": {
                        "dim": [{"size": "1"}, {"size": "8"}, {"size": "8"}, {"size": "6"}]
                    }
                }
            }
        },
    }
    (tmp_path / "model.json").write_text(json.dumps(model_json))
    return load_graph_model(tmp_path / "model.json")


def _conv_nhwc(x: np.ndarray, w: np.ndarray, stride: int, pad: tuple[int, int]) -> np.ndarray:
    """Plain convolution of one NHWC image with HWIO weights, TF's explicit padding."""
    x = np.pad(x[0], ((pad[0], pad[1]), (pad[0], pad[1]), (0, 0)))
    kh, kw = w.shape[:2]
    out_h = (x.shape[0] - kh) // stride + 1
    out_w = (x.shape[1] - kw) // stride + 1
    out = np.zeros((out_h, out_w, w.shape[3]))
    for r in range(out_h):
        for c in range(out_w):
            patch = x[r * stride : r * stride + kh, c * stride : c * stride + kw]
            out[r, c] = np.tensordot(patch, w, axes=([0, 1, 2], [0, 1, 2]))
    return out[None]


def _reference(x: np.ndarray, w: dict[str, np.ndarray]) -> np.ndarray:
    conv = np.clip(_conv_nhwc(x, w["conv/w"], 2, (0, 1)) + w["conv/b"], 0, 6)  # SAME, stride 2
    dw_w = w["dw/w"][:, :, :, 0]
    padded = np.pad(conv[0], ((1, 1), (1, 1), (0, 0)))
    dw = np.zeros_like(conv[0])
    for r in range(4):
        for c in range(4):
            dw[r, c] = (padded[r : r + 3, c : c + 3] * dw_w).sum(axis=(0, 1))
    scaled = dw * dw.mean(axis=(0, 1))
    # TF's asymmetric resize: output pixel i samples input i * 4 / 8.
    src = np.arange(8) * 0.5
    i0 = np.floor(src).astype(int)
    i1 = np.minimum(i0 + 1, 3)
    f = src - i0
    rows = scaled[i0] * (1 - f)[:, None, None] + scaled[i1] * f[:, None, None]
    up = rows[:, i0] * (1 - f)[None, :, None] + rows[:, i1] * f[None, :, None]
    side = _conv_nhwc(x, w["side/w"], 1, (0, 0))[0]
    return 1 / (1 + np.exp(-np.concatenate([up, side], axis=2)[None]))


def test_a_converted_graph_computes_what_the_tfjs_ops_mean(tmp_path: Path) -> None:
    rng = np.random.default_rng(3)
    model_json, weights = _graph(tmp_path, rng)
    assert weights["conv/w"].dtype == np.float32  # float16 shards dequantised
    model = convert(model_json, weights, {"out": "result"}, nhwc_outputs=["out"], input_name="x")
    x = rng.uniform(0, 1, size=(1, 8, 8, 3)).astype(np.float32)
    got = ort.InferenceSession(model.SerializeToString()).run(None, {"x": x})[0]
    np.testing.assert_allclose(got, _reference(x.astype(np.float64), weights), atol=1e-5)


def test_unknown_ops_and_short_shards_are_refused(tmp_path: Path) -> None:
    model_json, weights = _graph(tmp_path, np.random.default_rng(0))
    model_json["modelTopology"]["node"].append(_node("odd", "Erf", ["out"]))
    with pytest.raises(UnsupportedGraphError, match="Erf"):
        convert(model_json, weights, {"odd": "odd"})
    (tmp_path / "w.bin").write_bytes((tmp_path / "w.bin").read_bytes() + b"\0\0")
    with pytest.raises(UnsupportedGraphError, match="bytes"):
        read_weights(model_json, tmp_path)
