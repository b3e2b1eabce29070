"""Training the box refiner (PyTorch): rooms made by `data.make_rooms`, a scene per step,
smooth L1 on the log ratios, the learning rate annealed over the epochs; the epoch whose
refined boxes find most true boxes on the validation rooms is kept, exported to ONNX, checked
against PyTorch, and written with its normalisation, metrics and curve."""

from __future__ import annotations

import copy
import json
import sys
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np
import torch
from holiscene_schema import Box3D
from tqdm import tqdm

from ...evaluation.box_iou import iou_3d
from ...geometry.boxes import corners_of
from ...shapes import SIZE_RANGES
from ..export import keep_if_faithful
from .data import RoomSample, make_rooms
from .features import PAIR_FEATURES, TARGETS, feature_names, refined
from .net import BoxRefinerNet

MODEL_FILE = "model.onnx"
FOUND_IOU = 0.15  # the measure: a true box is found by a box with 3D IoU >= 0.15
EXPORT_TOLERANCE = 1e-4  # log ratios


@dataclass
class BoxRefinerTraining:
    out: Path
    rooms: int = 1500
    first_seed: int = 610000  # training rooms: first_seed, first_seed + 1, ...
    validation_rooms: int = 40
    validation_seed: int = 960000
    epochs: int = 30
    workers: int = 2
    seed: int = 0
    curve: list[dict[str, float]] = field(default_factory=list)


def _found(estimate: Box3D, truth: Box3D) -> bool:
    return iou_3d(corners_of(estimate), corners_of(truth)) >= FOUND_IOU


def _true_boxes(rooms: list[RoomSample]) -> int:
    return max(sum(len(room.truths) + room.missed for room in rooms), 1)


def pipeline_found_share(rooms: list[RoomSample]) -> float:
    """Share of the true boxes found at IoU 0.15 by the placement's boxes (fixed in training)."""
    found = sum(_found(e, t) for r in rooms for e, t in zip(r.estimates, r.truths, strict=True))
    return found / _true_boxes(rooms)


def refined_found_share(
    net: BoxRefinerNet, rooms: list[RoomSample], mean: torch.Tensor, std: torch.Tensor
) -> float:
    """Share of the true boxes found at IoU 0.15 by the boxes `net` refines."""
    net.eval()
    found = 0
    with torch.no_grad():
        for room in rooms:
            if not room.truths:
                continue
            x = (torch.from_numpy(room.features) - mean) / std
            predicted = net(x[None], torch.from_numpy(room.pairs)[None])[0].numpy()
            for estimate, truth, ratios in zip(room.estimates, room.truths, predicted, strict=True):
                found += _found(refined(estimate, ratios), truth)
    net.train()
    return found / _true_boxes(rooms)


def _gather(
    seeds: range, classes: list[str], workers: int, label: str, failures: list[str]
) -> list[RoomSample]:
    rooms: list[RoomSample] = []
    made = make_rooms(seeds, classes, workers)
    for room in tqdm(made, total=len(seeds), desc=label, unit="room", file=sys.stderr):
        if isinstance(room, str):
            failures.append(room)
            tqdm.write(f"skipped {room}", file=sys.stderr)
        else:
            rooms.append(room)
    return rooms


def export_onnx(net: BoxRefinerNet, path: Path, features: int) -> float:
    """Write the ONNX model to `path` only if it agrees with PyTorch within EXPORT_TOLERANCE
    on a random scene of another size than the traced one (so the object axis is dynamic);
    returns the largest difference."""
    net.eval()
    example = (torch.randn(1, 7, features), torch.randn(1, 7, 7, PAIR_FEATURES))
    tmp = path.with_suffix(".tmp.onnx")
    torch.onnx.export(
        net,
        example,
        str(tmp),
        input_names=["objects", "pairs"],
        output_names=["log_ratios"],
        dynamic_axes={
            "objects": {1: "n"},
            "pairs": {1: "n", 2: "n"},
            "log_ratios": {1: "n"},
        },
        opset_version=17,
        dynamo=False,
    )
    objects, pairs = torch.randn(1, 12, features), torch.randn(1, 12, 12, PAIR_FEATURES)
    with torch.no_grad():
        expected = net(objects, pairs).numpy()
    feeds = {"objects": objects.numpy(), "pairs": pairs.numpy()}
    return keep_if_faithful(tmp, path, feeds, "log_ratios", expected, EXPORT_TOLERANCE)


def _plot(curve: list[dict[str, float]], path: Path) -> None:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    figure, (loss_axis, found_axis) = plt.subplots(1, 2, figsize=(9, 3.5))
    epochs = [c["epoch"] for c in curve]
    loss_axis.plot(epochs, [c["train_loss"] for c in curve])
    loss_axis.set_xlabel("epoch")
    loss_axis.set_ylabel("training loss (smooth L1)")
    found_axis.plot(epochs, [100 * c["found_refined"] for c in curve], label="refined boxes")
    found_axis.plot(
        epochs, [100 * c["found_pipeline"] for c in curve], label="placement's boxes", ls="--"
    )
    found_axis.set_xlabel("epoch")
    found_axis.set_ylabel(f"validation boxes found at IoU {FOUND_IOU}, %")
    found_axis.legend()
    figure.tight_layout()
    figure.savefig(path, dpi=90)
    plt.close(figure)


def train_box_refiner(run: BoxRefinerTraining) -> dict[str, float]:
    torch.set_num_threads(1)
    torch.manual_seed(run.seed)
    run.out.mkdir(parents=True, exist_ok=True)
    classes = sorted(SIZE_RANGES)
    seeds = range(run.first_seed, run.first_seed + run.rooms)
    validation_seeds = range(run.validation_seed, run.validation_seed + run.validation_rooms)
    if set(seeds) & set(validation_seeds):
        raise ValueError("the training and validation seeds overlap")
    failures: list[str] = []
    made = _gather(seeds, classes, run.workers, "training rooms", failures)
    rooms = [r for r in made if r.truths]
    validation = _gather(validation_seeds, classes, run.workers, "validation rooms", failures)
    if not rooms:
        raise ValueError("no training room has a placed object")
    everything = torch.from_numpy(np.concatenate([r.features for r in rooms]))
    # A feature constant over the training rooms (a class the generator never makes) keeps
    # unit scale: dividing by its tiny spread would blow up any photo that has it.
    mean, spread = everything.mean(0), everything.std(0)
    std = torch.where(spread < 1e-3, torch.ones_like(spread), spread + 1e-3)
    data = [
        (
            (torch.from_numpy(r.features) - mean) / std,
            torch.from_numpy(r.pairs),
            torch.from_numpy(r.targets),
        )
        for r in rooms
    ]
    net = BoxRefinerNet(everything.shape[1])
    optimiser = torch.optim.AdamW(net.parameters(), lr=1e-3, weight_decay=0.01)
    schedule = torch.optim.lr_scheduler.CosineAnnealingLR(optimiser, run.epochs)
    pipeline_share = pipeline_found_share(validation)
    best: tuple[float, dict[str, torch.Tensor]] = (-1.0, {})
    for epoch in range(1, run.epochs + 1):
        losses = []
        for index in tqdm(
            torch.randperm(len(data)).tolist(), desc=f"epoch {epoch}", leave=False, file=sys.stderr
        ):
            x, pairs, y = data[index]
            loss = torch.nn.functional.smooth_l1_loss(net(x[None], pairs[None])[0], y, beta=0.1)
            optimiser.zero_grad()
            loss.backward()  # type: ignore[no-untyped-call]
            optimiser.step()
            losses.append(loss.item())
        schedule.step()
        refined_share = refined_found_share(net, validation, mean, std)
        run.curve.append(
            {
                "epoch": epoch,
                "train_loss": float(np.mean(losses)),
                "found_pipeline": pipeline_share,
                "found_refined": refined_share,
            }
        )
        print(json.dumps(run.curve[-1]), file=sys.stderr, flush=True)
        if refined_share > best[0]:
            best = (refined_share, copy.deepcopy(net.state_dict()))
    net.load_state_dict(best[1])
    difference = export_onnx(net, run.out / MODEL_FILE, everything.shape[1])
    best_epoch = max(run.curve, key=lambda c: c["found_refined"])
    metrics = {
        "validation_found_pipeline": pipeline_share,
        "validation_found_refined": best_epoch["found_refined"],
        "best_epoch": best_epoch["epoch"],
        "onnx_max_abs_difference": difference,
        "training_objects": int(everything.shape[0]),
        "rooms_the_pipeline_failed_on": len(failures),
    }
    (run.out / "metrics.json").write_text(json.dumps(metrics, indent=1) + "\n")
    metadata = {
        "model": MODEL_FILE,
        "inputs": ["objects", "pairs"],
        "output": "log_ratios",
        "targets": list(TARGETS),
        "classes": classes,
        "features": feature_names(classes),
        "mean": [round(float(v), 6) for v in mean],
        "std": [round(float(v), 6) for v in std],
        "found_iou": FOUND_IOU,
        "rooms": run.rooms,
        "first_seed": run.first_seed,
        "validation_rooms": run.validation_rooms,
        "validation_seed": run.validation_seed,
        "epochs": run.epochs,
        "seed": run.seed,
        "failed_rooms": failures,
        "curve": run.curve,
    }
    (run.out / "metadata.json").write_text(json.dumps(metadata, indent=1) + "\n")
    _plot(run.curve, run.out / "curve.png")
    return metrics
