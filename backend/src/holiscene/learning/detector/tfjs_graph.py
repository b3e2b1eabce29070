"""TensorFlow.js graph models (model.json + weight shards) read into plain Python and numpy.

Shared by the ONNX converter (tfjs_convert) and the PyTorch twin used for fine-tuning
(graph_torch), so both read the same graph the same way.
"""

from __future__ import annotations

import base64
import json
from pathlib import Path
from typing import Any

import numpy as np

_NUMPY_OF_DTYPE = {"float32": np.float32, "int32": np.int32, "bool": np.bool_}


class UnsupportedGraphError(ValueError):
    """The graph uses an op or attribute this code does not translate."""


def read_weights(model_json: dict[str, Any], weights_dir: Path) -> dict[str, np.ndarray]:
    """Every weight of the manifest, dequantised to its original dtype."""
    weights: dict[str, np.ndarray] = {}
    for group in model_json["weightsManifest"]:
        data = b"".join((weights_dir / path).read_bytes() for path in group["paths"])
        offset = 0
        for entry in group["weights"]:
            shape = [int(s) for s in entry["shape"]]
            count = int(np.prod(shape)) if shape else 1
            quant = entry.get("quantization")
            dtype: np.dtype[Any]
            values: np.ndarray
            if quant is None:
                dtype = np.dtype(_NUMPY_OF_DTYPE[entry["dtype"]])
                values = np.frombuffer(data, dtype, count, offset)
            elif quant["dtype"] == "float16":
                dtype = np.dtype(np.float16)
                values = np.frombuffer(data, dtype, count, offset).astype(np.float32)
            elif quant["dtype"] in ("uint8", "uint16"):
                dtype = np.dtype(quant["dtype"])
                raw = np.frombuffer(data, dtype, count, offset).astype(np.float32)
                values = raw * np.float32(quant["scale"]) + np.float32(quant["min"])
                values = values.astype(_NUMPY_OF_DTYPE[entry["dtype"]])
            else:
                raise UnsupportedGraphError(f"unknown weight quantisation {quant['dtype']!r}")
            offset += count * dtype.itemsize
            weights[entry["name"]] = np.array(values).reshape(shape)
        if offset != len(data):
            raise UnsupportedGraphError(
                f"weight shards hold {len(data)} bytes, the manifest names {offset}"
            )
    return weights


def attr(node: dict[str, Any], name: str) -> Any:
    value = node.get("attr", {}).get(name)
    if value is None:
        return None
    if "list" in value:
        items = value["list"]
        if "i" in items:
            return [int(i) for i in items["i"]]
        if "s" in items:
            return [base64.b64decode(s).decode() for s in items["s"]]
        return []
    if "s" in value:
        return base64.b64decode(value["s"]).decode()
    if "i" in value:
        return int(value["i"])
    if "b" in value:
        return bool(value["b"])
    if "f" in value:
        return float(value["f"])
    if "type" in value:
        return value["type"]
    return value


def tensor_name(tf_name: str) -> str:
    base, _, index = tf_name.partition(":")
    return base if index in ("", "0") else f"{base}:{index}"


def topological(nodes: list[dict[str, Any]]) -> list[dict[str, Any]]:
    """The graph's nodes ordered so that every input comes before its use."""
    by_name = {n["name"]: n for n in nodes}
    done: set[str] = set()
    order: list[dict[str, Any]] = []
    for start in nodes:
        stack = [(start["name"], False)]
        while stack:
            name, expanded = stack.pop()
            if name in done:
                continue
            if expanded:
                done.add(name)
                order.append(by_name[name])
                continue
            stack.append((name, True))
            for dependency in by_name[name].get("input", []):
                base = dependency.split(":")[0].lstrip("^")
                if base in by_name and base not in done:
                    stack.append((base, False))
    return order


def load_graph_model(model_file: Path) -> tuple[dict[str, Any], dict[str, np.ndarray]]:
    """A TF.js graph model's JSON and its weights, from the files npm ships."""
    model_json: dict[str, Any] = json.loads(model_file.read_text())
    return model_json, read_weights(model_json, model_file.parent)
