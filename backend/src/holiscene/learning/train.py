"""Train a support network on synthetic scenes plus labelled scenes; write a model directory.

`holiscene train-rn` and the app's retrain jobs both call `train_relation_model`. The run is
deterministic for a seed (one thread, seeded shuffles and augmentation), stops early when
validation accuracy has not improved for `patience` epochs, and keeps the best epoch.
"""

from __future__ import annotations

import json
import math
import platform
import random
import time
from collections.abc import Sequence
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np
import torch
import torch.nn.functional as F

from ..core.settings import REPO_ROOT
from .export import export_onnx
from .nets import SupportNet
from .priors import count_priors
from .samples import NO_LABEL, SupportSample
from .synthetic import seeds_digest, synthetic_samples
from .training_api import (
    CURVE_FILE,
    DATA_FILE,
    METRICS_FILE,
    MODEL_FILE,
    PRIORS_FILE,
    TrainConfig,
    TrainProgress,
    TrainResult,
    percent,
)

BATCH_SCENES = 8  # scenes per optimiser step (each scene is one forward pass)


def _tensors(sample: SupportSample) -> dict[str, torch.Tensor]:
    return {k: torch.from_numpy(v) for k, v in sample.inputs.items()}


def augment(inputs: dict[str, torch.Tensor], rng: random.Random) -> dict[str, torch.Tensor]:
    """Mirror left-right (supports do not care) and jitter colour and brightness."""
    image, masks, boxes = inputs["image"], inputs["masks"], inputs["boxes"]
    if rng.random() < 0.5:
        image = image.flip(-1)
        masks = masks.flip(-1)
        boxes = torch.stack([1 - boxes[:, 2], boxes[:, 1], 1 - boxes[:, 0], boxes[:, 3]], 1)
    gains = torch.tensor([rng.uniform(0.8, 1.2) for _ in range(3)]).reshape(1, 3, 1, 1)
    image = (image * gains + rng.uniform(-0.1, 0.1)).clamp(0, 1)
    return {"image": image, "masks": masks, "boxes": boxes, "classes": inputs["classes"]}


def scene_loss(net: SupportNet, sample: SupportSample, inputs: dict[str, torch.Tensor]) -> Any:
    logits = net(**inputs)
    return F.cross_entropy(
        logits.reshape(logits.shape[0], -1),
        torch.from_numpy(sample.targets),
        ignore_index=NO_LABEL,
        reduction="sum",
    )


def predicted_answers(net: SupportNet, sample: SupportSample) -> np.ndarray:
    with torch.no_grad():
        logits = net(**_tensors(sample))
    answers: np.ndarray = logits.reshape(logits.shape[0], -1).argmax(1).numpy()
    return answers


def accuracy(net: SupportNet, samples: Sequence[SupportSample]) -> float:
    """Share of labelled objects whose top answer (supporter and type) is right."""
    net.eval()
    right = total = 0
    for sample in samples:
        labelled = sample.targets != NO_LABEL
        right += int((predicted_answers(net, sample)[labelled] == sample.targets[labelled]).sum())
        total += int(labelled.sum())
    return right / total if total else 0.0


def split(
    samples: Sequence[SupportSample], fraction: float, seed: int
) -> tuple[list[SupportSample], list[SupportSample]]:
    order = list(range(len(samples)))
    random.Random(seed).shuffle(order)
    held = max(1, round(fraction * len(samples))) if len(samples) > 1 else 0
    return [samples[i] for i in order[held:]], [samples[i] for i in order[:held]]


@dataclass
class _Fit:
    """What the epochs left: the learning curve, the best epoch and why they stopped."""

    curve: list[dict[str, float]] = field(default_factory=list)
    best_accuracy: float = -1.0
    best_epoch: int = 0
    stopped: str = "max_epochs"


def train_relation_model(
    config: TrainConfig,
    labelled: Sequence[SupportSample],
    out_dir: Path,
    progress: TrainProgress | None = None,
) -> TrainResult:
    """Train on `config.synthetic_scenes` generated scenes plus `labelled`; write the model
    directory (ONNX, metrics, counted priors, what data it saw, curve) into `out_dir`."""
    say = progress or (lambda fraction, line: None)
    torch.manual_seed(config.seed)
    torch.set_num_threads(1)
    started = time.perf_counter()
    seeds = list(
        range(config.synthetic_seed_start, config.synthetic_seed_start + config.synthetic_scenes)
    )
    say(0.0, f"preparing {len(seeds)} synthetic scenes")
    synthetic = synthetic_samples(
        seeds,
        config.cache_dir,
        lambda done, total: say(0.25 * done / max(total, 1), f"synthetic scenes {done}/{total}"),
    )
    samples = [s for s in [*synthetic, *labelled] if s.labelled > 0]
    if not samples:
        raise ValueError("no labelled objects to train on")
    train, validation = split(samples, config.validation_fraction, config.seed)
    say(0.25, f"training on {len(train)} scenes, validating on {len(validation)}")

    net = SupportNet()
    fit = _fit(net, train, validation, config, say, started)
    out_dir.mkdir(parents=True, exist_ok=True)
    difference = export_onnx(net, validation[0] if validation else train[0], out_dir / MODEL_FILE)
    (out_dir / PRIORS_FILE).write_text(count_priors(train).to_json())
    metrics: dict[str, Any] = {
        "architecture": config.architecture,
        "validation_accuracy": fit.best_accuracy,
        "best_epoch": fit.best_epoch,
        "epochs": len(fit.curve),
        "stopped": fit.stopped,
        "onnx_max_difference": difference,
        "curve": fit.curve,
        **run_record(started, config),
    }
    (out_dir / METRICS_FILE).write_text(json.dumps(metrics, indent=1) + "\n")
    data = {
        "synthetic_seeds": {"start": seeds[0] if seeds else None, "count": len(seeds)},
        "synthetic_digest": seeds_digest(seeds),
        "labelled_scenes": [s.name for s in labelled],
        "train_scenes": len(train),
        "validation_scenes": [s.name for s in validation],
        "objects": int(sum(s.labelled for s in samples)),
    }
    (out_dir / DATA_FILE).write_text(json.dumps(data, indent=1) + "\n")
    plot_curve(fit.curve, out_dir / CURVE_FILE)
    say(1.0, f"done: validation accuracy {percent(fit.best_accuracy)} at epoch {fit.best_epoch}")
    return TrainResult(out_dir, fit.best_accuracy, metrics)


def _fit(
    net: SupportNet,
    train: Sequence[SupportSample],
    validation: Sequence[SupportSample],
    config: TrainConfig,
    say: TrainProgress,
    started: float,
) -> _Fit:
    """Run the epochs until patience, the epoch limit or the time budget ends them; leave
    the best epoch's weights in `net`."""
    optimiser = torch.optim.AdamW(net.parameters(), lr=config.learning_rate, weight_decay=1e-4)
    steps_per_epoch = math.ceil(len(train) / BATCH_SCENES)
    schedule = torch.optim.lr_scheduler.OneCycleLR(
        optimiser, config.learning_rate, total_steps=max(1, steps_per_epoch * config.max_epochs)
    )
    rng = random.Random(config.seed)
    fit = _Fit()
    best_state = net.state_dict()
    for epoch in range(1, config.max_epochs + 1):
        train_loss = _train_epoch(net, train, optimiser, schedule, rng)
        validation_accuracy = accuracy(net, validation)
        fit.curve.append(
            {
                "epoch": epoch,
                "train_loss": train_loss,
                "validation_accuracy": validation_accuracy,
                "seconds": time.perf_counter() - started,
            }
        )
        if validation_accuracy > fit.best_accuracy:
            fit.best_accuracy, fit.best_epoch = validation_accuracy, epoch
            best_state = {k: v.clone() for k, v in net.state_dict().items()}
        say(
            0.25 + 0.7 * epoch / config.max_epochs,
            f"epoch {epoch}: loss {train_loss:.3f}, "
            f"validation accuracy {percent(validation_accuracy)} "
            f"(best {percent(fit.best_accuracy)})",
        )
        if epoch - fit.best_epoch >= config.patience:
            fit.stopped = "early_stopping"
            break
        if config.time_budget_s and time.perf_counter() - started > config.time_budget_s:
            fit.stopped = "time_budget"
            break
    net.load_state_dict(best_state)
    return fit


def _train_epoch(
    net: SupportNet,
    train: Sequence[SupportSample],
    optimiser: torch.optim.Optimizer,
    schedule: torch.optim.lr_scheduler.LRScheduler,
    rng: random.Random,
) -> float:
    """One pass over the shuffled training scenes; the mean loss per labelled object."""
    net.train()
    order = list(range(len(train)))
    rng.shuffle(order)
    total_loss, objects = 0.0, 0
    for start in range(0, len(order), BATCH_SCENES):
        optimiser.zero_grad()
        for index in order[start : start + BATCH_SCENES]:
            sample = train[index]
            loss = scene_loss(net, sample, augment(_tensors(sample), rng))
            (loss / BATCH_SCENES).backward()
            total_loss += loss.item()
            objects += sample.labelled
        optimiser.step()
        schedule.step()
    return total_loss / max(objects, 1)


def run_record(started: float, config: object) -> dict[str, Any]:
    """What every training run's metrics.json says of how it ran: time, settings, machine."""
    return {
        "train_seconds": round(time.perf_counter() - started, 1),
        "config": {k: recorded_setting(v) for k, v in vars(config).items()},
        "machine": platform.platform(),
        "torch": torch.__version__,
    }


def recorded_setting(value: object) -> object:
    """A setting as metrics.json keeps it: paths inside the repository relative to it, so a
    committed model's record names no one's machine."""
    if not isinstance(value, Path):
        return value
    try:
        return str(value.resolve().relative_to(REPO_ROOT))
    except ValueError:
        return str(value)


def plot_curve(
    curve: Sequence[dict[str, float]],
    path: Path,
    accuracy_label: str = "validation support accuracy",
    loss_label: str = "train loss per object",
) -> None:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    from matplotlib.ticker import MaxNLocator, PercentFormatter

    fig, loss_axis = plt.subplots(figsize=(6, 3.5), dpi=100)
    epochs = [c["epoch"] for c in curve]
    # Marks as well as lines: a short retrain's one or two epochs would draw no line at all.
    # Two shapes, the loss's larger: with one epoch both points may sit at the same height.
    few = len(epochs) <= 20
    accuracy_axis = loss_axis.twinx()
    series = (
        (loss_axis, "train_loss", "tab:red", "s", 7, "train loss", loss_label),
        (accuracy_axis, "validation_accuracy", "tab:blue", "o", 4, "validation", accuracy_label),
    )
    for axis, key, colour, mark, size, label, axis_label in series:
        values = [c[key] for c in curve]
        marker = mark if few else None
        axis.plot(epochs, values, color=colour, marker=marker, markersize=size, label=label)
        axis.set_ylabel(axis_label, color=colour)
    loss_axis.set_xlabel("epoch")
    accuracy_axis.set_ylim(0, 1)
    # In percent, as the models page and the training log give the figures.
    accuracy_axis.yaxis.set_major_formatter(PercentFormatter(xmax=1))
    # Epochs are whole. The locator falls back to fractions when fewer than two whole numbers
    # are in view (one epoch: 0.945-1.05), so a short run gets its epochs as the ticks.
    if 0 < len(epochs) < 5:  # an untrained model's curve is empty
        loss_axis.set_xlim(epochs[0] - 0.5, epochs[-1] + 0.5)
        loss_axis.set_xticks(epochs)
    else:
        loss_axis.xaxis.set_major_locator(MaxNLocator(integer=True))
    # One legend for the two axes' lines, above the plot: inside it ("best" weighs only the
    # axis it belongs to) it covered the first epoch's loss.
    lines = loss_axis.get_lines() + accuracy_axis.get_lines()
    fig.legend(
        lines,
        [str(line.get_label()) for line in lines],
        loc="upper center",
        ncol=len(lines),
        frameon=False,
    )
    fig.tight_layout(rect=(0, 0, 1, 0.9))
    fig.savefig(path)
    plt.close(fig)
