"""ONNX export of a support network, checked against PyTorch before it is written."""

from __future__ import annotations

from collections.abc import Callable
from pathlib import Path

import numpy as np
import onnxruntime as ort
import torch
from holiscene_schema.relation_model import INPUT_NAMES, OPSET, OUTPUT_NAME

from .samples import SupportSample

# On the logits, which a long-trained net drives to tens: float32 in another order of operations
# differs by some 1e-5 there (a 30-epoch retrain on 1500 scenes ended at 1.9e-5 and was thrown
# away), while a wrong export differs by far more.
EXPORT_TOLERANCE = 1e-4


def export_onnx(net: torch.nn.Module, example: SupportSample, path: Path) -> float:
    """Write `net` to `path` with a dynamic object count; returns the largest difference
    between onnxruntime and PyTorch on `example` (raises if above EXPORT_TOLERANCE)."""
    net = net.eval()
    args = tuple(torch.from_numpy(example.inputs[name]) for name in INPUT_NAMES)
    tmp = path.with_suffix(".tmp.onnx")
    n = torch.export.Dim("objects", min=1, max=256)
    torch.onnx.export(
        net,
        args,
        str(tmp),
        input_names=list(INPUT_NAMES),
        output_names=[OUTPUT_NAME],
        opset_version=OPSET,
        dynamo=True,
        external_data=False,
        dynamic_shapes={"image": {}, "masks": {0: n}, "boxes": {0: n}, "classes": {0: n}},
    )
    with torch.no_grad():
        expected = net(*args).numpy()
    feeds = {k: example.inputs[k] for k in INPUT_NAMES}
    return keep_if_faithful(tmp, path, feeds, OUTPUT_NAME, expected, EXPORT_TOLERANCE)


def largest_difference(actual: np.ndarray, expected: np.ndarray) -> float:
    return float(np.abs(actual - expected).max())


def keep_if_faithful(
    exported: Path,
    path: Path,
    feeds: dict[str, np.ndarray],
    output_name: str,
    expected: np.ndarray,
    tolerance: float,
    measure: Callable[[np.ndarray, np.ndarray], float] = largest_difference,
) -> float:
    """Run the `exported` ONNX file on `feeds`; move it to `path` when its output is within
    `tolerance` of PyTorch's `expected` (by `measure`, element by element unless told
    otherwise), else delete it and raise. Returns the difference."""
    session = ort.InferenceSession(str(exported), providers=["CPUExecutionProvider"])
    got = session.run([output_name], feeds)[0]
    difference = measure(np.asarray(got), expected)
    if difference > tolerance:
        exported.unlink()
        raise RuntimeError(f"ONNX export differs from PyTorch by {difference:.2e}")
    exported.replace(path)
    return difference
