"""Training the completion network on partial scans of the furniture library (PyTorch).

`train_completion` makes the scans, trains for a wall-clock budget with the learning rate
annealed over it, exports the ONNX model, checks it against PyTorch, and writes
model.onnx, metadata.json, metrics.json and curve.png into the output folder.
"""

from __future__ import annotations

import json
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np
import torch

from ..budget import plot_curve, train_for_budget
from .net import GROWN_PER_SKELETON, CompletionNet, chamfer
from .scans import (
    KEEP_BOUND,
    PARTIAL_POINTS,
    SKELETON_POINTS,
    SURFACE_POINTS,
    FloatArray,
    make_samples,
)

MODEL_FILE = "model.onnx"
TARGET_SUBSAMPLE = 1024  # surface points compared per step (a fresh subset each time)


@dataclass
class CompletionTraining:
    out: Path
    train_scans: int = 5000
    validation_scans: int = 200
    seed: int = 0
    time_budget: float = 900.0
    batch: int = 16
    curve: list[dict[str, float]] = field(default_factory=list)


def _tensors(arrays: dict[str, FloatArray]) -> dict[str, torch.Tensor]:
    return {name: torch.from_numpy(value) for name, value in arrays.items()}


def _loss(net: CompletionNet, batch: dict[str, torch.Tensor]) -> torch.Tensor:
    skeleton, coarse, completed = net(batch["partial"])
    pick = torch.randperm(SURFACE_POINTS)[:TARGET_SUBSAMPLE]
    surface = batch["surface"][:, pick]
    grown = completed[:, : coarse.shape[1]]
    loss: torch.Tensor = (
        chamfer(skeleton, batch["skeleton"]) + chamfer(coarse, surface) + chamfer(grown, surface)
    )
    return loss


def _mirrored(batch: dict[str, torch.Tensor]) -> dict[str, torch.Tensor]:
    """Left-right mirror (z -> -z) of a random half: furniture has no handedness."""
    flip = torch.where(torch.rand(batch["partial"].shape[0]) < 0.5, -1.0, 1.0)
    scale = torch.stack([torch.ones_like(flip), torch.ones_like(flip), flip], dim=1)[:, None, :]
    return {name: value * scale for name, value in batch.items()}


def mean_chamfer_l2(predicted: np.ndarray, truth: np.ndarray) -> float:
    """Chamfer distance as the thesis reports it: mean nearest distance both ways, halved."""
    from ...evaluation.shape_metrics import chamfer_distance

    values = [chamfer_distance(p, t) for p, t in zip(predicted, truth, strict=True)]
    return float(np.mean(values))


def _validate(net: CompletionNet, validation: dict[str, torch.Tensor]) -> dict[str, float]:
    net.eval()
    with torch.no_grad():
        _, _, completed = net(validation["partial"])
    net.train()
    truth = validation["surface"].numpy()
    return {
        "completed_chamfer": mean_chamfer_l2(completed.numpy(), truth),
        "partial_chamfer": mean_chamfer_l2(validation["partial"].numpy(), truth),
    }


def _train_loop(
    run: CompletionTraining,
    net: CompletionNet,
    data: dict[str, torch.Tensor],
    validation: dict[str, torch.Tensor],
) -> None:
    count = data["partial"].shape[0]

    def step_loss() -> torch.Tensor:
        index = torch.randint(count, (run.batch,))
        return _loss(net, _mirrored({name: value[index] for name, value in data.items()}))

    optimiser = torch.optim.Adam(net.parameters(), lr=1e-3)
    train_for_budget(
        optimiser, step_loss, lambda: _validate(net, validation), run.time_budget, run.curve
    )


def export_onnx(net: CompletionNet, path: Path) -> float:
    """Write the ONNX model; the largest difference from PyTorch on random scans."""
    import onnxruntime as ort

    net.eval()
    example = torch.rand(2, PARTIAL_POINTS, 3) - 0.5
    torch.onnx.export(
        net,
        (example,),
        str(path),
        input_names=["partial"],
        output_names=["skeleton", "coarse", "completed"],
        dynamic_axes={
            "partial": {0: "batch"},
            "skeleton": {0: "batch"},
            "coarse": {0: "batch"},
            "completed": {0: "batch"},
        },
        opset_version=17,
        dynamo=False,
    )
    with torch.no_grad():
        expected = net(example)[2].numpy()
    session = ort.InferenceSession(str(path), providers=["CPUExecutionProvider"])
    got = session.run(["completed"], {"partial": example.numpy()})[0]
    return float(np.abs(got - expected).max())


def train_completion(run: CompletionTraining) -> dict[str, float]:
    torch.set_num_threads(1)
    torch.manual_seed(run.seed)
    run.out.mkdir(parents=True, exist_ok=True)
    data = _tensors(make_samples(run.train_scans, run.seed))
    validation = _tensors(make_samples(run.validation_scans, run.seed + 1_000_003))
    net = CompletionNet()
    _train_loop(run, net, data, validation)
    final = _validate(net, validation)
    difference = export_onnx(net, run.out / MODEL_FILE)
    if difference > 1e-3:
        raise RuntimeError(f"the ONNX model differs from PyTorch by {difference}")
    metrics = {
        **final,
        "onnx_max_abs_difference": difference,
        "steps": run.curve[-1]["step"] if run.curve else 0,
    }
    (run.out / "metrics.json").write_text(json.dumps(metrics, indent=1) + "\n")
    metadata = {
        "model": MODEL_FILE,
        "input": "partial",
        "partial_points": PARTIAL_POINTS,
        "skeleton_points": SKELETON_POINTS,
        "grown_per_skeleton": GROWN_PER_SKELETON,
        "keep_bound": KEEP_BOUND,
        "frame": "object box mapped onto [-0.5, 0.5]^3, x front, y up, z right",
        "train_scans": run.train_scans,
        "validation_scans": run.validation_scans,
        "seed": run.seed,
        "time_budget_s": run.time_budget,
        "batch": run.batch,
        "curve": run.curve,
    }
    (run.out / "metadata.json").write_text(json.dumps(metadata, indent=1) + "\n")
    plot_curve(
        run.curve,
        run.out / "curve.png",
        {"completed_chamfer": "completed points", "partial_chamfer": "partial points"},
        "validation Chamfer (box units)",
    )
    return metrics
