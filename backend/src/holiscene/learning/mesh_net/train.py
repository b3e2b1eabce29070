"""Training the mesh network on library objects seen from room viewpoints (PyTorch).

`train_mesh_net` makes the samples, trains for a wall-clock budget (learning rate annealed over
it), chooses the face-cutting threshold on the validation samples, exports the ONNX model,
checks it against PyTorch, and writes model.onnx, metadata.json, metrics.json and curve.png.

Distances are measured as `holiscene eval --shapes` measures them: in the box's frame scaled
so its longest side is 1.
"""

from __future__ import annotations

import math
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
from .config import MeshNetTraining
from .inputs import (
    CONDITION_SIZE,
    MAX_TEMPLATE_VERTICES,
    MESH_CLASSES,
    SILHOUETTE_PIXELS,
    VERTEX_FEATURES,
)
from .net import MeshNet, chamfer
from .samples import TEMPLATE_SAMPLES, TRUTH_POINTS, make_samples

MODEL_FILE = "model.onnx"
TRUTH_SUBSAMPLE = 1024  # truth points compared per step (a fresh subset each time)
ERROR_WEIGHT = 0.5
OFFSET_WEIGHT = 0.01
# Face-cutting thresholds tried on the validation samples (eval-frame distance; inf: no cut).
CUT_CHOICES = (math.inf, 0.12, 0.09, 0.07, 0.05, 0.04, 0.03)
MIN_KEPT = 0.5  # never cut more than half of a mesh's surface


def sample_points(
    vertices: torch.Tensor, indices: torch.Tensor, weights: torch.Tensor
) -> torch.Tensor:
    """Surface samples of a (moved) mesh: barycentric weights (B, P, 3) of vertex indices."""
    batch = torch.arange(vertices.shape[0])[:, None, None]
    corners = vertices[batch, indices.long()]  # (B, P, 3, 3)
    return (corners * weights[..., None]).sum(dim=2)


def _step_loss(net: MeshNet, batch: dict[str, torch.Tensor]) -> torch.Tensor:
    moved, error = net(batch["silhouette"], batch["condition"], batch["template"])
    scale = batch["scale"][:, None, :]
    points = sample_points(moved, batch["sample_vertices"], batch["sample_weights"]) * scale
    pick = torch.randperm(TRUTH_POINTS)[:TRUTH_SUBSAMPLE]
    truth = batch["truth"][:, pick] * scale
    distance = chamfer(points, truth)
    # The error head learns each moved vertex's distance to the truth (not pushed by it).
    with torch.no_grad():
        vertex_distance = torch.cdist(moved * scale, truth).min(dim=2).values
    valid = torch.arange(MAX_TEMPLATE_VERTICES)[None, :] < batch["vertex_count"][:, None]
    error_loss = ((error - vertex_distance).abs() * valid).sum() / valid.sum()
    offsets = ((moved - batch["template"][..., :3]) ** 2).sum(dim=2)
    offset_loss = (offsets * valid).sum() / valid.sum()
    loss: torch.Tensor = distance.mean() + ERROR_WEIGHT * error_loss + OFFSET_WEIGHT * offset_loss
    return loss


def validation_scores(
    net: MeshNet, validation: dict[str, torch.Tensor], thresholds: tuple[float, ...] = (math.inf,)
) -> tuple[float, list[float]]:
    """Mean Chamfer of the template, and of the moved template cut at each threshold (inf:
    not cut)."""
    net.eval()
    with torch.no_grad():
        moved, error = net(
            validation["silhouette"], validation["condition"], validation["template"]
        )
    net.train()
    scale = validation["scale"][:, None, :]
    truth = validation["truth"] * scale
    indices, weights = validation["sample_vertices"], validation["sample_weights"]
    template = sample_points(validation["template"][..., :3], indices, weights) * scale
    points = sample_points(moved, indices, weights) * scale
    sample_error = error[torch.arange(len(error))[:, None, None], indices.long()].amax(dim=2)
    cut = []
    for threshold in thresholds:
        if math.isinf(threshold):
            cut.append(float(chamfer(points, truth).mean()))
            continue
        values = []
        for i in range(len(points)):
            keep = sample_error[i] <= threshold
            if keep.float().mean() < MIN_KEPT:
                keep = sample_error[i] <= sample_error[i].median()
            values.append(chamfer(points[i][keep][None], truth[i][None]))
        cut.append(float(torch.cat(values).mean()))
    return float(chamfer(template, truth).mean()), cut


def _train_loop(
    run: MeshNetTraining,
    net: MeshNet,
    data: dict[str, torch.Tensor],
    validation: dict[str, torch.Tensor],
) -> None:
    def step_loss() -> torch.Tensor:
        return _step_loss(net, random_batch(data, run.batch))

    def validate() -> dict[str, float]:
        template_chamfer, (moved_chamfer,) = validation_scores(net, validation)
        return {"template_chamfer": template_chamfer, "moved_chamfer": moved_chamfer}

    optimiser = torch.optim.Adam(net.parameters(), lr=1e-3)
    train_for_budget(
        optimiser, step_loss, validate, run.time_budget, run.curve, floor=0.03, checks=15
    )


def export_onnx(net: MeshNet, path: Path) -> float:
    """Write the ONNX model; the largest difference from PyTorch on random inputs (raises when
    too large)."""
    example = (
        (torch.rand(2, SILHOUETTE_PIXELS, SILHOUETTE_PIXELS) > 0.5).float(),
        torch.rand(2, CONDITION_SIZE),
        torch.rand(2, 300, VERTEX_FEATURES) - 0.5,
    )
    return export_checked_onnx(
        net,
        example,
        path,
        input_names=["silhouette", "condition", "template"],
        output_names=["vertices", "error"],
        dynamic_axes={
            "silhouette": {0: "batch"},
            "condition": {0: "batch"},
            "template": {0: "batch", 1: "vertices"},
            "vertices": {0: "batch", 1: "vertices"},
            "error": {0: "batch", 1: "vertices"},
        },
    )


def train_mesh_net(run: MeshNetTraining) -> dict[str, float]:
    torch.set_num_threads(2)
    torch.manual_seed(run.seed)
    run.out.mkdir(parents=True, exist_ok=True)
    data = as_tensors(make_samples(run.train_views, run.seed))
    validation = as_tensors(make_samples(run.validation_views, run.seed + 1_000_003))
    net = MeshNet()
    _train_loop(run, net, data, validation)
    template_chamfer, cut = validation_scores(net, validation, CUT_CHOICES)  # CUT_CHOICES[0]: inf
    best = int(np.argmin(cut))
    difference = export_onnx(net, run.out / MODEL_FILE)
    metrics = {
        "template_chamfer": template_chamfer,
        "moved_chamfer": cut[0],
        "cut_chamfer": cut[best],
        "onnx_max_abs_difference": difference,
        "steps": run.curve[-1]["step"] if run.curve else 0,
    }
    metadata = {
        "model": MODEL_FILE,
        "inputs": ["silhouette", "condition", "template"],
        "classes": list(MESH_CLASSES),
        "silhouette_pixels": SILHOUETTE_PIXELS,
        # null: cutting made no validation mesh closer to its truth, so nothing is cut.
        "cut_threshold": None if math.isinf(CUT_CHOICES[best]) else CUT_CHOICES[best],
        "cut_chamfer": dict(zip(map(str, CUT_CHOICES), cut, strict=True)),
        "min_kept": MIN_KEPT,
        "frame": "template in the box mapped onto [-0.5, 0.5]^3, x front, y up, z right",
        "train_views": run.train_views,
        "validation_views": run.validation_views,
        "template_samples": TEMPLATE_SAMPLES,
    }
    write_run_files(
        run,
        metrics,
        metadata,
        {"moved_chamfer": "deformed template", "template_chamfer": "template"},
        "validation Chamfer (longest side = 1)",
    )
    return metrics
