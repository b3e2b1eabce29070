"""The Surface Network: a small encoder-decoder that reads a 128x96 photo and labels each cell
of a 64x48 grid as floor, ceiling, front wall or side wall (`geometry.surface_labels`); trained
on synthetic rooms with exact labels and exported to ONNX for the layout stage.

`holiscene train-surfaces` calls `train_surface_model`. The layout stage scores room
hypotheses by how well their labels agree with the network's (`geometry.surface_map`), which
tells walls apart where they share one paint and one line is all that separates them.
"""

from __future__ import annotations

import itertools
import json
import time
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np
import torch
import torch.nn.functional as F
from torch import Tensor, nn

from ..geometry.surface_labels import INPUT_SIZE, MAP_SIZE, SURFACE_CLASSES, normalised_batch
from .export import keep_if_faithful
from .surface_data import SurfaceSet, surface_set
from .train import plot_curve, run_record
from .training_api import CURVE_FILE, METRICS_FILE, MODEL_FILE, TrainProgress, percent

INPUT_NAME, OUTPUT_NAME = "image", "surface_logits"
OPSET = 18
EXPORT_TOLERANCE = 1e-4


def _block(c_in: int, c_out: int, stride: int = 1) -> nn.Sequential:
    return nn.Sequential(
        nn.Conv2d(c_in, c_out, 3, stride, 1, bias=False),
        nn.BatchNorm2d(c_out),
        nn.ReLU(inplace=True),
        nn.Conv2d(c_out, c_out, 3, 1, 1, bias=False),
        nn.BatchNorm2d(c_out),
        nn.ReLU(inplace=True),
    )


class SurfaceNet(nn.Module):
    """U-Net-like: five halvings from 128x96 to 4x3 cells, a whole-image context vector added
    at the bottom (a room's layout is a global thing), and skips back up to the 64x48 map.
    Sized for CPU training: one step on 16 photos takes about 0.5 s on one core."""

    def __init__(self, widths: tuple[int, ...] = (16, 24, 32, 48, 64)) -> None:
        super().__init__()
        self.down = nn.ModuleList(
            [_block(3, widths[0], stride=2)]
            + [_block(a, b, stride=2) for a, b in itertools.pairwise(widths)]
        )
        self.context = nn.Sequential(nn.Linear(widths[-1], widths[-1]), nn.ReLU(inplace=True))
        self.up = nn.ModuleList([_block(b + a, a) for a, b in itertools.pairwise(widths)])
        self.head = nn.Conv2d(widths[0], len(SURFACE_CLASSES), 1)

    def forward(self, image: Tensor) -> Tensor:
        skips = []
        x = image
        for stage in self.down:
            x = stage(x)
            skips.append(x)
        x = x + self.context(x.mean(dim=(2, 3)))[:, :, None, None]
        for stage, skip in zip(reversed(self.up), reversed(skips[:-1]), strict=True):
            x = F.interpolate(x, size=skip.shape[2:], mode="bilinear", align_corners=False)
            x = stage(torch.cat([x, skip], dim=1))
        result: Tensor = self.head(x)
        return result


@dataclass(frozen=True)
class SurfaceTrainConfig:
    seed: int = 0
    train_seeds: tuple[int, int] = (500_000, 600)  # (first seed, count)
    validation_seeds: tuple[int, int] = (510_000, 100)
    epochs: int = 30
    batch: int = 16
    learning_rate: float = 3e-3
    cache_dir: Path | None = None


def _batch_tensors(images: np.ndarray, labels: np.ndarray) -> tuple[Tensor, Tensor]:
    return torch.from_numpy(normalised_batch(images)), torch.from_numpy(labels.astype(np.int64))


def _augment(
    images: np.ndarray, labels: np.ndarray, rng: np.random.Generator
) -> tuple[np.ndarray, np.ndarray]:
    """Mirror left-right (labels do not change: a side wall stays a side wall) and change
    brightness, contrast and tint, so paint and light colours do not decide the labels."""
    flip = rng.random(len(images)) < 0.5
    images = np.where(flip[:, None, None, None], images[:, :, ::-1], images).astype(np.float32)
    labels = np.where(flip[:, None, None], labels[:, :, ::-1], labels)
    gain = rng.uniform(0.7, 1.3, (len(images), 1, 1, 3)) * rng.uniform(
        0.8, 1.2, (len(images), 1, 1, 1)
    )
    offset = rng.uniform(-25, 25, (len(images), 1, 1, 1))
    return np.clip(images * gain + offset, 0, 255), labels


def pixel_accuracy(net: SurfaceNet, data: SurfaceSet, batch: int = 50) -> float:
    net.eval()
    right = 0
    with torch.no_grad():
        for start in range(0, len(data), batch):
            x, y = _batch_tensors(
                data.images[start : start + batch], data.labels[start : start + batch]
            )
            right += int((net(x).argmax(1) == y).sum())
    return right / data.labels.size


def export_surface_onnx(net: SurfaceNet, example: Tensor, path: Path) -> float:
    """Write the network with a fixed input size; returns the largest difference between
    onnxruntime and PyTorch on `example` (raises above EXPORT_TOLERANCE)."""
    net = net.eval()
    tmp = path.with_suffix(".tmp.onnx")
    torch.onnx.export(
        net, (example,), str(tmp), input_names=[INPUT_NAME], output_names=[OUTPUT_NAME],
        opset_version=OPSET, dynamo=True, external_data=False,
    )  # fmt: skip
    with torch.no_grad():
        expected = net(example).numpy()
    feeds = {INPUT_NAME: example.numpy()}
    return keep_if_faithful(tmp, path, feeds, OUTPUT_NAME, expected, EXPORT_TOLERANCE)


def train_surface_model(
    config: SurfaceTrainConfig, out_dir: Path, progress: TrainProgress | None = None
) -> dict[str, Any]:
    """Render (or read cached) synthetic rooms, train, keep the best epoch by validation pixel
    accuracy, and write model.onnx, metrics.json and curve.png into `out_dir`."""
    say = progress or (lambda fraction, line: None)
    torch.manual_seed(config.seed)
    rng = np.random.default_rng(config.seed)
    started = time.perf_counter()

    def seeds(first_count: tuple[int, int]) -> list[int]:
        return list(range(first_count[0], first_count[0] + first_count[1]))

    say(0.0, "rendering validation rooms")
    validation = surface_set(seeds(config.validation_seeds), config.cache_dir)
    train = surface_set(
        seeds(config.train_seeds),
        config.cache_dir,
        lambda done, total: say(0.3 * done / total, f"training rooms {done}/{total}"),
    )
    net = SurfaceNet()
    optimiser = torch.optim.AdamW(net.parameters(), lr=config.learning_rate, weight_decay=1e-4)
    steps = -(-len(train) // config.batch)
    schedule = torch.optim.lr_scheduler.OneCycleLR(
        optimiser, config.learning_rate, total_steps=steps * config.epochs
    )
    curve: list[dict[str, float]] = []
    best, best_state, best_epoch = -1.0, net.state_dict(), 0
    for epoch in range(1, config.epochs + 1):
        net.train()
        order = rng.permutation(len(train))
        total = 0.0
        for start in range(0, len(order), config.batch):
            index = order[start : start + config.batch]
            x, y = _batch_tensors(*_augment(train.images[index], train.labels[index], rng))
            loss = F.cross_entropy(net(x), y)
            optimiser.zero_grad()
            loss.backward()  # type: ignore[no-untyped-call]
            optimiser.step()
            schedule.step()
            total += loss.item() * len(index)
        accuracy = pixel_accuracy(net, validation)
        curve.append({
            "epoch": epoch, "train_loss": total / len(train), "validation_accuracy": accuracy,
            "seconds": time.perf_counter() - started,
        })  # fmt: skip
        if accuracy > best:
            best, best_epoch = accuracy, epoch
            best_state = {k: v.clone() for k, v in net.state_dict().items()}
        say(
            0.3 + 0.65 * epoch / config.epochs,
            f"epoch {epoch}: loss {curve[-1]['train_loss']:.3f}, "
            f"validation pixel accuracy {percent(accuracy)} (best {percent(best)})",
        )
    net.load_state_dict(best_state)
    out_dir.mkdir(parents=True, exist_ok=True)
    example, _ = _batch_tensors(validation.images[:1], validation.labels[:1])
    difference = export_surface_onnx(net, example, out_dir / MODEL_FILE)
    metrics = {
        "classes": list(SURFACE_CLASSES),
        "input_size": list(INPUT_SIZE),
        "map_size": list(MAP_SIZE),
        "validation_pixel_accuracy": best,
        "best_epoch": best_epoch,
        "onnx_max_difference": difference,
        "curve": curve,
        **run_record(started, config),
    }
    (out_dir / METRICS_FILE).write_text(json.dumps(metrics, indent=1) + "\n")
    plot_curve(curve, out_dir / CURVE_FILE, "validation pixel accuracy", "train loss per pixel")
    say(1.0, f"done: validation pixel accuracy {percent(best)} at epoch {best_epoch}")
    return metrics
