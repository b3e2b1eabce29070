"""What a scene network (LEN + ODN) training run is asked for (no PyTorch here: the CLI reads the
defaults without importing it)."""

from __future__ import annotations

from dataclasses import dataclass


@dataclass(frozen=True)
class SceneNetTrainConfig:
    rooms: int = 2400
    validation_rooms: int = 200
    budget_s: float = 1200.0
    batch: int = 16
    learning_rate: float = 1e-3
    hidden: int = 256
    views: int = 2  # randomised views of each training room
    weight_decay: float = 0.01
    seed: int = 0
    threads: int = 2
