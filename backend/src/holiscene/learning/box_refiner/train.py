"""Training the box refiner (PyTorch): rooms made by `data.make_rooms`; several members, each
from its own seed, trained a scene per step on the Laplace likelihood of the log ratios (each
target's error scaled by the member's own expected error, so the few boxes the geometry put far
off weigh less), the learning rate annealed over the epochs, each member kept at the epoch whose
refined boxes find most true boxes on the validation rooms. The members' ensemble is exported to
ONNX and checked against PyTorch; the confidence (`confidence.py`) is fitted on the validation
rooms; all is written with the normalisation, metrics and curves."""

from __future__ import annotations

import copy
import json
import multiprocessing
import sys
from collections.abc import Iterable
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np
import torch
from holiscene_schema import Box3D
from tqdm import tqdm

from ...evaluation.box_iou import iou_3d
from ...geometry.boxes import corners_of
from ...shapes import SIZE_RANGES
from ..export import keep_if_faithful
from .confidence import FOUND_IOU, confidence_features, fit_confidence
from .config import BoxRefinerTraining
from .data import RoomCache, RoomSample, make_rooms
from .features import PAIR_FEATURES, TARGETS, feature_names, refined
from .net import OUTPUT_PARTS, BoxRefinerEnsemble, BoxRefinerNet

MODEL_FILE = "model.onnx"
OUTPUT_NAME = "refinement"
EXPORT_TOLERANCE = 1e-4  # log ratios


@dataclass(frozen=True)
class Normalised:
    """The training rooms' features standardised, as tensors, and the standardisation."""

    mean: torch.Tensor
    std: torch.Tensor
    scenes: list[tuple[torch.Tensor, torch.Tensor, torch.Tensor]]  # features, pairs, targets

    def inputs(self, room: RoomSample) -> tuple[torch.Tensor, torch.Tensor]:
        x = (torch.from_numpy(room.features) - self.mean) / self.std
        return x[None], torch.from_numpy(room.pairs)[None]


def _found(estimate: Box3D, truth: Box3D) -> bool:
    return iou_3d(corners_of(estimate), corners_of(truth)) >= FOUND_IOU


def _true_boxes(rooms: list[RoomSample]) -> int:
    return max(sum(len(room.truths) + room.missed for room in rooms), 1)


def _share(found: Iterable[bool], rooms: list[RoomSample]) -> float:
    """Share of the rooms' true boxes that `found` says were found (missed ones count too)."""
    return sum(found) / _true_boxes(rooms)


def pipeline_found_share(rooms: list[RoomSample]) -> float:
    """Share of the true boxes found at IoU 0.15 by the placement's boxes (fixed in training)."""
    return _share(
        (_found(e, t) for r in rooms for e, t in zip(r.estimates, r.truths, strict=True)), rooms
    )


def _refined_boxes(
    net: torch.nn.Module, rooms: list[RoomSample], data: Normalised
) -> list[tuple[Box3D, Box3D, np.ndarray]]:
    """(refined box, true box, the net's output row) for every matched box of `rooms`."""
    net.eval()
    out = []
    with torch.no_grad():
        for room in rooms:
            if not room.truths:
                continue
            rows = net(*data.inputs(room))[0].numpy()
            for estimate, truth, row in zip(room.estimates, room.truths, rows, strict=True):
                out.append((refined(estimate, row[: len(TARGETS)]), truth, row))
    net.train()
    return out


def refined_found_share(net: torch.nn.Module, rooms: list[RoomSample], data: Normalised) -> float:
    """Share of the true boxes found at IoU 0.15 by the boxes `net` refines."""
    return _share((_found(box, truth) for box, truth, _ in _refined_boxes(net, rooms, data)), rooms)


def laplace_loss(output: torch.Tensor, target: torch.Tensor) -> torch.Tensor:
    """Negative log likelihood of the targets under a Laplace distribution per target, centred
    on the predicted log ratio with the predicted log scale (constants dropped)."""
    n = len(TARGETS)
    ratios, log_scales = output[..., :n], output[..., n:]
    return ((target - ratios).abs() * torch.exp(-log_scales) + log_scales).mean()


def _gather(
    seeds: range,
    classes: list[str],
    run: BoxRefinerTraining,
    label: str,
    failures: list[str],
) -> list[RoomSample]:
    rooms: list[RoomSample] = []
    cache = RoomCache(run.room_cache, classes) if run.room_cache else None
    made = make_rooms(seeds, classes, run.workers, cache)
    for room in tqdm(made, total=len(seeds), desc=label, unit="room", file=sys.stderr):
        if isinstance(room, str):
            failures.append(room)
            tqdm.write(f"skipped {room}", file=sys.stderr)
        else:
            rooms.append(room)
    return rooms


def _normalise(rooms: list[RoomSample]) -> Normalised:
    everything = torch.from_numpy(np.concatenate([r.features for r in rooms]))
    # A feature constant over the training rooms (a class the generator never makes) keeps
    # unit scale: dividing by its tiny spread would blow up any photo that has it.
    mean, spread = everything.mean(0), everything.std(0)
    std = torch.where(spread < 1e-3, torch.ones_like(spread), spread + 1e-3)
    scenes = [
        (
            (torch.from_numpy(r.features) - mean) / std,
            torch.from_numpy(r.pairs),
            torch.from_numpy(r.targets),
        )
        for r in rooms
    ]
    return Normalised(mean, std, scenes)


Curve = list[dict[str, float]]


def train_member(
    data: Normalised, validation: list[RoomSample], run: BoxRefinerTraining, member: int
) -> tuple[BoxRefinerNet, Curve]:
    """One network from seed `run.seed + member`, at its best validation epoch, and its
    curve."""
    torch.manual_seed(run.seed + member)
    net = BoxRefinerNet(int(data.mean.shape[0]))
    optimiser = torch.optim.AdamW(net.parameters(), lr=1e-3, weight_decay=0.01)
    schedule = torch.optim.lr_scheduler.CosineAnnealingLR(optimiser, run.epochs)
    curve: Curve = []
    best: tuple[float, dict[str, torch.Tensor]] = (-1.0, {})
    label = f"member {member + 1}/{run.members}"
    for epoch in range(1, run.epochs + 1):
        losses = []
        order = torch.randperm(len(data.scenes)).tolist()
        for index in tqdm(order, desc=f"{label} epoch {epoch}", leave=False, file=sys.stderr):
            x, pairs, y = data.scenes[index]
            loss = laplace_loss(net(x[None], pairs[None])[0], y)
            optimiser.zero_grad()
            loss.backward()  # type: ignore[no-untyped-call]
            optimiser.step()
            losses.append(loss.item())
        schedule.step()
        share = refined_found_share(net, validation, data)
        curve.append({"epoch": epoch, "train_loss": float(np.mean(losses)), "found": share})
        print(json.dumps({"member": member + 1, **curve[-1]}), file=sys.stderr, flush=True)
        if share > best[0]:
            best = (share, copy.deepcopy(net.state_dict()))
    net.load_state_dict(best[1])
    return net, curve


# A member process's training data, set once per process by its pool's initializer.
_WORKER_DATA: dict[str, Any] = {}


def _start_member_process(rooms: list[RoomSample], validation: list[RoomSample]) -> None:
    # The rooms come as numpy (tensors would travel as one shared file each: thousands), and
    # are normalised here as in the parent, to the same figures.
    torch.set_num_threads(1)
    _WORKER_DATA["data"] = _normalise(rooms)
    _WORKER_DATA["validation"] = validation


def _member_in_process(run: BoxRefinerTraining, member: int) -> tuple[dict[str, Any], Curve]:
    net, curve = train_member(_WORKER_DATA["data"], _WORKER_DATA["validation"], run, member)
    return {name: value.numpy() for name, value in net.state_dict().items()}, curve


def train_members(
    rooms: list[RoomSample], data: Normalised, validation: list[RoomSample], run: BoxRefinerTraining
) -> list[BoxRefinerNet]:
    """The ensemble's members trained on `rooms` (normalised as `data`), `run.workers` at a
    time (each on one thread: the same networks as one after the other, as each member's
    seed fixes its own randomness); their curves go to `run.curves`."""
    if run.workers <= 1 or run.members <= 1:
        trained = [train_member(data, validation, run, k) for k in range(run.members)]
    else:
        context = multiprocessing.get_context("spawn")
        workers = min(run.workers, run.members)
        with context.Pool(workers, _start_member_process, (rooms, validation)) as pool:
            states = pool.starmap(_member_in_process, [(run, k) for k in range(run.members)])
        trained = []
        for state, curve in states:
            net = BoxRefinerNet(int(data.mean.shape[0]))
            net.load_state_dict({name: torch.from_numpy(value) for name, value in state.items()})
            trained.append((net, curve))
    run.curves.extend(curve for _, curve in trained)
    return [net for net, _ in trained]


def export_onnx(net: BoxRefinerEnsemble, path: Path, features: int) -> float:
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
        output_names=[OUTPUT_NAME],
        dynamic_axes={
            "objects": {1: "n"},
            "pairs": {1: "n", 2: "n"},
            OUTPUT_NAME: {1: "n"},
        },
        opset_version=17,
        dynamo=False,
    )
    objects, pairs = torch.randn(1, 12, features), torch.randn(1, 12, 12, PAIR_FEATURES)
    with torch.no_grad():
        expected = net(objects, pairs).numpy()
    feeds = {"objects": objects.numpy(), "pairs": pairs.numpy()}
    return keep_if_faithful(tmp, path, feeds, OUTPUT_NAME, expected, EXPORT_TOLERANCE)


def plot_curves(
    curves: list[list[dict[str, float]]], pipeline_share: float, ensemble_share: float, path: Path
) -> None:
    """The members' training losses and validation shares, with the placement's share and
    the ensemble's (each member at its kept epoch)."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    figure, (loss_axis, found_axis) = plt.subplots(1, 2, figsize=(9, 3.5))
    for member, curve in enumerate(curves, start=1):
        epochs = [c["epoch"] for c in curve]
        loss_axis.plot(epochs, [c["train_loss"] for c in curve], label=f"member {member}")
        found_axis.plot(epochs, [100 * c["found"] for c in curve], label=f"member {member}")
    found_axis.axhline(100 * pipeline_share, color="grey", ls="--", label="placement's boxes")
    found_axis.axhline(100 * ensemble_share, color="black", label="the ensemble")
    loss_axis.set_xlabel("epoch")
    loss_axis.set_ylabel("training loss (Laplace NLL)")
    found_axis.set_xlabel("epoch")
    found_axis.set_ylabel(f"validation boxes found at IoU {FOUND_IOU}, %")
    found_axis.legend(fontsize="small")
    figure.tight_layout()
    figure.savefig(path, dpi=90)
    plt.close(figure)


def _fit_confidence_on(
    boxes: list[tuple[Box3D, Box3D, np.ndarray]], found: np.ndarray
) -> tuple[dict[str, Any], dict[str, float]]:
    """The confidence model fitted on the validation rooms' refined boxes (`_refined_boxes`)
    and whether each was found (as JSON), and how it fits there: the boxes' mean chance
    against the share found."""
    n = len(TARGETS)
    if not boxes:
        raise ValueError("no validation room has a placed object to fit the confidence on")
    features = np.stack(
        [confidence_features(b, row[n : 2 * n], row[2 * n :]) for b, _, row in boxes]
    )
    model = fit_confidence(features, found)
    chances = model.chance(features)
    fit = {
        "validation_mean_confidence": float(chances.mean()),
        "validation_share_of_boxes_right": float(found.mean()),
        "validation_brier_score": float(np.mean((chances - found) ** 2)),
    }
    return model.to_json(), fit


def train_box_refiner(run: BoxRefinerTraining) -> dict[str, Any]:
    torch.set_num_threads(1)
    run.out.mkdir(parents=True, exist_ok=True)
    classes = sorted(SIZE_RANGES)
    seeds = range(run.first_seed, run.first_seed + run.rooms)
    validation_seeds = range(run.validation_seed, run.validation_seed + run.validation_rooms)
    if set(seeds) & set(validation_seeds):
        raise ValueError("the training and validation seeds overlap")
    failures: list[str] = []
    made = _gather(seeds, classes, run, "training rooms", failures)
    rooms = [r for r in made if r.truths]
    validation = _gather(validation_seeds, classes, run, "validation rooms", failures)
    if not rooms:
        raise ValueError("no training room has a placed object")
    data = _normalise(rooms)
    members = train_members(rooms, data, validation, run)
    ensemble = BoxRefinerEnsemble(members)
    pipeline_share = pipeline_found_share(validation)
    # The ensemble's validation boxes, refined once for its share and the confidence's fit.
    boxes = _refined_boxes(ensemble, validation, data)
    found = np.array([_found(box, truth) for box, truth, _ in boxes], dtype=bool)
    ensemble_share = _share(found.tolist(), validation)
    confidence, fit = _fit_confidence_on(boxes, found)
    features = int(data.mean.shape[0])
    metrics = {
        "validation_found_pipeline": pipeline_share,
        "validation_found_refined": ensemble_share,
        "validation_found_by_member": [max(c["found"] for c in curve) for curve in run.curves],
        "best_epoch_by_member": [
            max(curve, key=lambda c: c["found"])["epoch"] for curve in run.curves
        ],
        **fit,
        "onnx_max_abs_difference": export_onnx(ensemble, run.out / MODEL_FILE, features),
        "training_objects": sum(len(r.targets) for r in rooms),
        "rooms_the_pipeline_failed_on": len(failures),
    }
    (run.out / "metrics.json").write_text(json.dumps(metrics, indent=1) + "\n")
    metadata = {
        "model": MODEL_FILE,
        "inputs": ["objects", "pairs"],
        "output": OUTPUT_NAME,
        "output_columns": [f"{t} {part}" for part in OUTPUT_PARTS for t in TARGETS],
        "targets": list(TARGETS),
        "classes": classes,
        "features": feature_names(classes),
        "mean": [round(float(v), 6) for v in data.mean],
        "std": [round(float(v), 6) for v in data.std],
        "confidence": confidence,
        "found_iou": FOUND_IOU,
        "rooms": run.rooms,
        "first_seed": run.first_seed,
        "validation_rooms": run.validation_rooms,
        "validation_seed": run.validation_seed,
        "epochs": run.epochs,
        "members": run.members,
        "seed": run.seed,
        "failed_rooms": failures,
        "curves": run.curves,
    }
    (run.out / "metadata.json").write_text(json.dumps(metadata, indent=1) + "\n")
    plot_curves(run.curves, pipeline_share, ensemble_share, run.out / "curve.png")
    return metrics
