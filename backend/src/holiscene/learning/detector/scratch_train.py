"""Train the from-scratch detector (scratch_net) on synthetic rooms (PyTorch, CPU).

`holiscene train-detector --from-scratch` calls `train_scratch_detector`. Each training room
is randomised `views` times (data.randomise) and halved once to the net's input; an epoch
takes one view of each room, and each batch flips half its photos. The learning rate warms up,
then follows a cosine over the run, whose length is the planned epochs or the wall-clock
budget, whichever ends first, so a run on a busy machine still anneals before it stops. The
best epoch by validation mAP@0.5 is exported as one ONNX file of the detector contract, with
metadata.json, metrics.json and curve.png.
"""

from __future__ import annotations

import math
import time
from collections.abc import Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np
import torch
from holiscene_schema.detector_model import INPUT_SIZE

from ..training_api import TrainProgress
from .data import BoxedPhoto, center_targets, classes_in
from .epoch_record import EpochRecord
from .runtime import MODEL_FILE, preprocess
from .scratch_net import CELLS, STRIDE, ScratchDetector, ScratchNet, export_scratch_detector, halve
from .train import FeatureSet, detection_loss, extract, score_raw

WARMUP = 0.03  # share of the run the learning rate rises over


@dataclass(frozen=True)
class ScratchTrainConfig:
    seed: int = 0
    epochs: int = 12
    batch: int = 16
    learning_rate: float = 2e-3
    views: int = 2  # randomised views of each training room
    time_budget_s: float | None = None  # stop (annealed) after this many seconds of training
    threads: int = 2


def _encode(tensor: np.ndarray) -> tuple[np.ndarray, np.ndarray, None]:
    halved = halve(tensor)
    return halved, halved, None


def _batch(
    data: FeatureSet, index: np.ndarray, num_classes: int, rng: np.random.Generator
) -> tuple[torch.Tensor, torch.Tensor, list[tuple[int, int, int]], torch.Tensor]:
    """Images and targets of `index`, half of them flipped: (images, heatmaps, centre cells
    as (sample, row, column), their target sides)."""
    images: list[np.ndarray] = []
    heatmaps: list[np.ndarray] = []
    sides: list[np.ndarray] = []
    cells: list[tuple[int, int, int]] = []
    for b, n in enumerate(index):
        image, boxes = data.features[n], data.boxes[n]
        if rng.random() < 0.5:
            image = image[:, :, ::-1]
            boxes = boxes.copy()
            boxes[:, [0, 2]] = INPUT_SIZE - data.boxes[n][:, [2, 0]]
        heat, centres, box_sides = center_targets(
            boxes, data.class_index[n], num_classes, CELLS, STRIDE
        )
        images.append(image)
        heatmaps.append(heat)
        cells.extend((b, int(row), int(col)) for row, col in centres)
        sides.extend(box_sides)
    return (
        torch.from_numpy(np.stack(images).astype(np.float32)),
        torch.from_numpy(np.stack(heatmaps)),
        cells,
        torch.from_numpy(np.array(sides, np.float32).reshape(-1, 4)),
    )


def validation_map(net: ScratchNet, data: FeatureSet, classes: list[str]) -> float:
    """mAP@0.5 over the model's classes on validation photos (the contract's decoding)."""
    detector = ScratchDetector(net).eval()
    with torch.no_grad():
        raw_outputs = (
            _decode_halved(detector, data.features[n : n + 1]) for n in range(len(data.features))
        )
        return score_raw(raw_outputs, data, classes, set(classes))[0]


def _decode_halved(detector: ScratchDetector, halved: np.ndarray) -> np.ndarray:
    logits, sides = detector.net(torch.from_numpy(halved.astype(np.float32)))
    return detector.decode(logits, sides).numpy()


def _learning_rate(config: ScratchTrainConfig, done: float) -> float:
    """Warm-up then cosine, `done` the share of the run behind us."""
    if done < WARMUP:
        return config.learning_rate * (0.1 + 0.9 * done / WARMUP)
    return config.learning_rate * 0.5 * (1 + math.cos(math.pi * min(1.0, done)))


def _share_done(config: ScratchTrainConfig, step: int, steps: int, seconds: float) -> float:
    by_steps = step / steps
    if config.time_budget_s is None:
        return by_steps
    return max(by_steps, seconds / config.time_budget_s)


def _fit(
    net: ScratchNet,
    train: FeatureSet,
    validation: FeatureSet,
    classes: list[str],
    config: ScratchTrainConfig,
    say: TrainProgress,
    run_started: float,
) -> EpochRecord:
    """Train `net` in place; leaves it at its best evaluation. The record's times count from
    `run_started` (the photos' preparation included); the time budget from here."""
    rng = np.random.default_rng(config.seed)
    optimiser = torch.optim.AdamW(net.parameters(), lr=config.learning_rate, weight_decay=1e-4)
    rooms = len(train.features) // config.views
    per_epoch = -(-rooms // config.batch)
    steps, step, started = per_epoch * config.epochs, 0, time.perf_counter()
    record = EpochRecord(net, run_started)
    done = 0.0
    for epoch in range(1, config.epochs + 1):
        net.train()
        total, seen = 0.0, 0
        # One view of each room (a room's views are consecutive).
        order = rng.permutation(rooms) * config.views + rng.integers(0, config.views, rooms)
        for start in range(0, len(order), config.batch):
            done = _share_done(config, step, steps, time.perf_counter() - started)
            if done >= 1.0:
                break
            for group in optimiser.param_groups:
                group["lr"] = _learning_rate(config, done)
            images, heat, cells, target_sides = _batch(
                train, order[start : start + config.batch], len(classes), rng
            )
            logits, sides = net(images)
            loss = detection_loss(logits, sides, heat, cells, target_sides)
            optimiser.zero_grad()
            loss.backward()  # type: ignore[no-untyped-call]
            optimiser.step()
            step += 1
            total += loss.item() * len(images)
            seen += len(images)
        done = _share_done(config, step, steps, time.perf_counter() - started)
        net.eval()
        score = validation_map(net, validation, classes)
        line = record.add(epoch, total / max(seen, 1), score, photos_seen=seen)
        say(min(1.0, done), f"{line}, {(time.perf_counter() - started) / 60:.1f} min")
        if done >= 1.0:
            break
    record.keep_best()
    return record


def train_scratch_detector(
    train_photos: Sequence[BoxedPhoto],
    validation_photos: Sequence[BoxedPhoto],
    config: ScratchTrainConfig,
    out_dir: Path,
    progress: TrainProgress | None = None,
) -> dict[str, Any]:
    say = progress or (lambda fraction, line: None)
    started = time.perf_counter()
    torch.manual_seed(config.seed)
    torch.set_num_threads(config.threads)
    rng = np.random.default_rng(config.seed)
    classes = classes_in(train_photos)
    views = [p for p in train_photos for _ in range(config.views)]
    train = extract(views, classes, _encode, rng, False, say, "training photos")
    validation = extract(validation_photos, classes, _encode, None, False, say, "validation")
    prepared = time.perf_counter() - started
    net = ScratchNet(len(classes))
    record = _fit(net, train, validation, classes, config, say, started)
    out_dir.mkdir(parents=True, exist_ok=True)
    example = preprocess(validation_photos[0].rgb)
    difference = export_scratch_detector(net, example, out_dir / MODEL_FILE)
    metrics = {
        "classes": classes,
        "train_photos": len(train_photos),
        "train_views": len(views),
        "validation_photos": len(validation_photos),
        "parameters": sum(p.numel() for p in net.parameters()),
        "prepare_seconds": round(prepared, 1),
        "export_difference": difference,
    }
    metadata = {
        "name": "NYU-40 detector trained from scratch on synthetic rooms",
        "label_space": "nyu40",
        "classes": classes,
        "provenance": {
            "weights": "none pretrained: trained by holiscene train-detector --from-scratch on "
            "the photos in metrics.json",
        },
    }
    return record.write_files(out_dir, config, metrics, metadata)
