"""Train the layout and object networks together on synthetic rooms (`holiscene
train-3d scene-net`, `make scene-net-model`): render the rooms (or reuse a cache), read their
features once, train for a wall-clock budget with the learning rate annealed
(`learning.budget`), export to ONNX (checked against PyTorch) and write metadata.json,
metrics.json and curve.png beside it."""

from __future__ import annotations

import json
import time
from collections.abc import Sequence
from pathlib import Path
from typing import Any

import numpy as np
import torch

from ..budget import plot_curve, train_for_budget
from ..detector.backbone import FeatureExtractor
from ..detector.data import render_rooms
from ..detector.runtime import COCO_DETECTOR_DIR, MODEL_FILE
from ..train import run_record
from .config import SceneNetTrainConfig
from .evaluate import ValidationScores, score_predictions
from .net import Batch, SceneNet, export_scene_net, joint_loss
from .samples import PhotoSample, room_samples

METADATA_FILE = "metadata.json"
TRAIN_SEED, VALIDATION_SEED = 600000, 660000


def batch_of(samples: Sequence[PhotoSample]) -> Batch:
    """Photos padded to the most objects among them (padding: zero inputs, `valid` 0)."""
    size, n = len(samples), max(max(len(s.bbox) for s in samples), 1)

    def padded(
        name: str, shape: tuple[int, ...], dtype: torch.dtype = torch.float32
    ) -> torch.Tensor:
        out = torch.zeros((size, n, *shape), dtype=dtype)
        for i, s in enumerate(samples):
            values = np.asarray(getattr(s, name), dtype=np.float32)
            out[i, : len(values)] = torch.from_numpy(values).to(dtype)
        return out

    pairs = torch.zeros(size, n, n, 4)
    valid = torch.zeros(size, n)
    for i, s in enumerate(samples):
        count = len(s.bbox)
        pairs[i, :count, :count] = torch.from_numpy(s.pairs)
        valid[i, :count] = 1.0
    room_bins = torch.from_numpy(np.stack([s.room_bins for s in samples]))
    object_bins = padded("object_bins", (4,))

    def stack(name: str) -> torch.Tensor:
        return torch.from_numpy(
            np.stack([np.asarray(getattr(s, name), np.float32) for s in samples])
        )

    return Batch(
        room=stack("room"),
        camera=stack("camera"),
        objects=padded("objects", (samples[0].objects.shape[1],)),
        pairs=pairs,
        valid=valid,
        room_bins={
            name: (room_bins[:, i, 0].long(), room_bins[:, i, 1])
            for i, name in enumerate(("pitch", "roll", "yaw"))
        },
        log_height=stack("log_height")[:, 0],
        log_distances=stack("log_distances"),
        centre_offset=padded("centre_offset", (2,)),
        object_bins={
            "distance": (object_bins[..., 0].long(), object_bins[..., 1]),
            "yaw": (object_bins[..., 2].long(), object_bins[..., 3]),
        },
        log_size=padded("log_size", (3,)),
        bbox=padded("bbox", (4,)),
        typical_size=padded("typical_size", (3,)),
        true_corners=padded("true_corners", (8, 3)),
        world_from_pixel=stack("world_from_pixel"),
    )


def _standardisation(
    samples: Sequence[PhotoSample],
) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    from .net import STANDARDISED

    rooms = np.stack([s.room.astype(np.float32) for s in samples])
    room_mean, room_std = rooms.mean(axis=(0, 2, 3)), rooms.std(axis=(0, 2, 3)) + 1e-3
    objects = np.concatenate([s.objects[:, :STANDARDISED].astype(np.float32) for s in samples])
    return room_mean, room_std, objects.mean(axis=0), objects.std(axis=0) + 1e-3


def predict(net: SceneNet, samples: Sequence[PhotoSample]) -> list[tuple[np.ndarray, np.ndarray]]:
    """The raw rows of each photo, one photo at a time as at run time."""
    net.eval()
    out = []
    with torch.no_grad():
        for s in samples:
            batch = batch_of([s])
            room_rows, object_rows = net(batch.room, batch.camera, batch.objects, batch.pairs)
            out.append((room_rows[0].numpy(), object_rows[0, : len(s.bbox)].numpy()))
    net.train()
    return out


def train_scene_net(
    out_dir: Path, cache_dir: Path, config: SceneNetTrainConfig = SceneNetTrainConfig()
) -> dict[str, Any]:
    """Render, read, train, export; returns the metrics written to metrics.json."""
    started = time.perf_counter()
    torch.manual_seed(config.seed)
    torch.set_num_threads(config.threads)
    rng = np.random.default_rng(config.seed)
    train_seeds = range(TRAIN_SEED, TRAIN_SEED + config.rooms)
    validation_seeds = range(VALIDATION_SEED, VALIDATION_SEED + config.validation_rooms)
    folders = render_rooms(
        [*train_seeds, *validation_seeds], cache_dir / "rooms", workers=config.threads
    )
    extractor = FeatureExtractor(COCO_DETECTOR_DIR / MODEL_FILE, threads=config.threads)
    features_dir = cache_dir / "features"
    training = [
        sample
        for view in range(config.views)
        for sample in room_samples(
            extractor, [folders[s] for s in train_seeds], features_dir, config.seed + view, True
        )
    ]
    validation = room_samples(
        extractor, [folders[s] for s in validation_seeds], features_dir, 0, False
    )
    net = SceneNet(*_standardisation(training), hidden=config.hidden)
    optimiser = torch.optim.AdamW(
        net.parameters(), lr=config.learning_rate, weight_decay=config.weight_decay
    )
    curve: list[dict[str, float]] = []
    last_parts: dict[str, float] = {}

    def step_loss() -> torch.Tensor:
        chosen = rng.choice(len(training), size=min(config.batch, len(training)), replace=False)
        loss, parts = joint_loss(net, batch_of([training[i] for i in chosen]))
        last_parts.update(parts)
        return loss

    def validate() -> dict[str, float]:
        scores = score_predictions(validation, predict(net, validation))
        return {**scores.as_dict(), **{f"train_{k}": v for k, v in last_parts.items()}}

    train_for_budget(optimiser, step_loss, validate, config.budget_s, curve, config.learning_rate)
    final: ValidationScores = score_predictions(validation, predict(net, validation))
    out_dir.mkdir(parents=True, exist_ok=True)
    model_path = out_dir / "model.onnx"
    export_scene_net(net, str(model_path))
    difference = _check_export(net, model_path, validation[:5])
    metrics = {
        "validation": final.as_dict(),
        "export_max_difference": difference,
        "curve": curve,
        "rooms": {"train_seed": TRAIN_SEED, "validation_seed": VALIDATION_SEED},
        **run_record(started, config),
    }
    (out_dir / "metrics.json").write_text(json.dumps(metrics, indent=1))
    (out_dir / METADATA_FILE).write_text(
        json.dumps(
            {
                "description": "LEN + ODN (thesis Ch. 5) on the COCO backbone",
                "hidden": config.hidden,
            },
            indent=1,
        )
    )
    plot_curve(
        curve,
        out_dir / "curve.png",
        {"layout_iou": "layout 3D IoU", "boxes_found": "boxes found at IoU 0.15"},
        "validation share",
    )
    return metrics


def _check_export(net: SceneNet, model_path: Path, samples: Sequence[PhotoSample]) -> float:
    """The ONNX model's largest difference from PyTorch on a few photos."""
    import onnxruntime as ort

    session = ort.InferenceSession(str(model_path), providers=["CPUExecutionProvider"])
    worst = 0.0
    for sample, (room_rows, object_rows) in zip(samples, predict(net, samples), strict=True):
        batch = batch_of([sample])
        room_out, objects_out = session.run(
            None,
            {
                "room": batch.room.numpy(),
                "camera": batch.camera.numpy(),
                "objects": batch.objects.numpy(),
                "pairs": batch.pairs.numpy(),
            },
        )
        worst = max(worst, float(np.abs(room_out[0] - room_rows).max()))
        worst = max(worst, float(np.abs(objects_out[0] - object_rows).max()))
    if worst > 1e-3:
        raise RuntimeError(f"the exported scene network differs from PyTorch by {worst}")
    return worst
