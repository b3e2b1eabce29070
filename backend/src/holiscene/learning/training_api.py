"""What a training run takes and gives back; shared by `holiscene train-rn` and retrain jobs.

Kept free of PyTorch so the server can describe, queue and record training runs without
importing it; `holiscene.learning.train.train_relation_model` does the work.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any, Literal

Architecture = Literal["support_net", "thesis_rn"]
# progress(fraction done in [0, 1], one line for the job log)
TrainProgress = Callable[[float, str], None]


def percent(share: float) -> str:
    """A share as the training log, the job's result line and the models page write it:
    "97.1%"."""
    return f"{100 * share:.1f}%"


# The files a trained model directory holds.
MODEL_FILE = "model.onnx"
METRICS_FILE = "metrics.json"
PRIORS_FILE = "priors.json"
DATA_FILE = "data.json"
CURVE_FILE = "curve.png"


@dataclass(frozen=True)
class TrainConfig:
    seed: int = 0
    architecture: Architecture = "support_net"
    synthetic_scenes: int = 1200  # generated scenes (seeds from synthetic_seed_start on)
    synthetic_seed_start: int = 100_000
    validation_fraction: float = 0.15
    max_epochs: int = 40
    patience: int = 5  # epochs without a better validation accuracy before stopping
    time_budget_s: float | None = None  # stop after this many seconds of training
    learning_rate: float = 2e-3
    cache_dir: Path | None = None  # where generated synthetic samples are cached


@dataclass
class TrainResult:
    model_dir: Path  # holds MODEL_FILE, METRICS_FILE, PRIORS_FILE, DATA_FILE, CURVE_FILE
    validation_accuracy: float
    metrics: dict[str, Any] = field(default_factory=dict)
