"""What a box refiner training run is asked for (no PyTorch here: the CLI reads the defaults
without importing it)."""

from __future__ import annotations

from dataclasses import dataclass, field
from pathlib import Path


@dataclass
class BoxRefinerTraining:
    out: Path
    rooms: int = 12000
    first_seed: int = 610000  # training rooms: first_seed, first_seed + 1, ...
    validation_rooms: int = 200
    validation_seed: int = 960000
    epochs: int = 30
    members: int = 5  # networks in the ensemble, trained from seeds seed, seed + 1, ...
    workers: int = 2
    seed: int = 0
    room_cache: Path | None = None  # rooms kept between runs (data.RoomCache)
    curves: list[list[dict[str, float]]] = field(default_factory=list)  # per member
