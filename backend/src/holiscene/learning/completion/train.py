"""Training the completion network on partial scans of the furniture library (PyTorch).

`train_completion` makes the scans, trains for a wall-clock budget with the learning rate
annealed over it, exports the ONNX model, checks it against PyTorch, and writes
model.onnx, metadata.json, metrics.json and curve.png into the output folder.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from pathlib import Path

import numpy as np
import torch

from ..budget import (
    as_tensors,
    export_checked_onnx,
    random_batch,
    train_for_budget,
    write_run_files,
)
from .net import GROWN_PER_SKELETON, CompletionNet, chamfer
from .scans import (
    KEEP_BOUND,
    PARTIAL_POINTS,
    SKELETON_POINTS,
    SURFACE_POINTS,
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
    def step_loss() -> torch.Tensor:
        return _loss(net, _mirrored(random_batch(data, run.batch)))

    optimiser = torch.optim.Adam(net.parameters(), lr=1e-3)
    train_for_budget(
        optimiser, step_loss, lambda: _validate(net, validation), run.time_budget, run.curve
    )


def export_onnx(net: CompletionNet, path: Path) -> float:
    """Write the ONNX model; the largest difference of the completed points from PyTorch on
    random scans (raises when too large)."""
    outputs = ["skeleton", "coarse", "completed"]
    return export_checked_onnx(
        net,
        (torch.rand(2, PARTIAL_POINTS, 3) - 0.5,),
        path,
        input_names=["partial"],
        output_names=outputs,
        dynamic_axes={name: {0: "batch"} for name in ["partial", *outputs]},
        checked=["completed"],  # the only output the run time reads
    )


def train_completion(run: CompletionTraining) -> dict[str, float]:
    torch.set_num_threads(1)
    torch.manual_seed(run.seed)
    run.out.mkdir(parents=True, exist_ok=True)
    data = as_tensors(make_samples(run.train_scans, run.seed))
    validation = as_tensors(make_samples(run.validation_scans, run.seed + 1_000_003))
    net = CompletionNet()
    _train_loop(run, net, data, validation)
    final = _validate(net, validation)
    difference = export_onnx(net, run.out / MODEL_FILE)
    metrics = {
        **final,
        "onnx_max_abs_difference": difference,
        "steps": run.curve[-1]["step"] if run.curve else 0,
    }
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
    }
    write_run_files(
        run,
        metrics,
        metadata,
        {"completed_chamfer": "completed points", "partial_chamfer": "partial points"},
        "validation Chamfer (box units)",
    )
    return metrics
