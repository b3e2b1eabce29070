"""What a mesh network training run is asked for (no PyTorch here: the CLI reads the defaults
without importing it)."""

from __future__ import annotations

from dataclasses import dataclass, field
from pathlib import Path


@dataclass
class MeshNetTraining:
    out: Path
    train_views: int = 16000
    validation_views: int = 400
    seed: int = 0
    time_budget: float = 1500.0
    batch: int = 32
    curve: list[dict[str, float]] = field(default_factory=list)
