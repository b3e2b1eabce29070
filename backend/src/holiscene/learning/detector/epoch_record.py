"""What every detector trainer keeps of its epochs: the curve (for curve.png and
metrics.json) and the weights of its best epoch by validation mAP@0.5, kept in the end; and
the files every trained detector directory holds besides its model."""

from __future__ import annotations

import json
import time
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import torch
from torch import nn

from ..train import plot_curve, run_record
from .runtime import METADATA_FILE


@dataclass
class EpochRecord:
    net: nn.Module
    started: float = field(default_factory=time.perf_counter)
    curve: list[dict[str, float]] = field(default_factory=list)
    best: float = -1.0
    best_epoch: int = 0
    best_state: dict[str, torch.Tensor] | None = None

    def add(self, epoch: int, train_loss: float, score: float, **extra: float) -> str:
        """Record one epoch (the net as it is now); the progress line that says it."""
        self.curve.append({
            "epoch": epoch, "train_loss": train_loss, "validation_accuracy": score,
            "seconds": time.perf_counter() - self.started, **extra,
        })  # fmt: skip
        if score > self.best:
            self.best, self.best_epoch = score, epoch
            self.best_state = {k: v.clone() for k, v in self.net.state_dict().items()}
        return (
            f"epoch {epoch}: loss {train_loss:.3f}, validation mAP@0.5 {100 * score:.1f}% "
            f"(best {100 * self.best:.1f}%)"
        )

    def keep_best(self) -> None:
        """Put the best epoch's weights back, for evaluation."""
        if self.best_state is not None:
            self.net.load_state_dict(self.best_state)
        self.net.eval()

    def write_files(
        self, out_dir: Path, config: object, metrics: dict[str, Any], metadata: dict[str, Any]
    ) -> dict[str, Any]:
        """metrics.json (the given figures, the best epoch, the curve and how the run went),
        metadata.json and curve.png into `out_dir`; the metrics."""
        metrics = {
            **metrics,
            "best_epoch": self.best_epoch,
            "validation_map_at_0_5": self.best,
            "curve": self.curve,
            **run_record(self.started, config),
        }
        (out_dir / "metrics.json").write_text(json.dumps(metrics, indent=1, default=str) + "\n")
        (out_dir / METADATA_FILE).write_text(json.dumps(metadata, indent=2) + "\n")
        plot_curve(self.curve, out_dir / "curve.png", "validation mAP@0.5", "train loss per photo")
        return metrics
