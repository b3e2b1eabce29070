"""Typical object sizes (metres) per NYU-40 class: depth (front-back), height, width."""

from __future__ import annotations

TYPICAL_SIZE_M: dict[str, tuple[float, float, float]] = {
    "bed": (2.0, 0.6, 1.6),
    "chair": (0.55, 0.9, 0.5),
    "sofa": (0.9, 0.85, 2.0),
    "table": (0.8, 0.75, 1.2),
    "desk": (0.7, 0.75, 1.3),
    "dresser": (0.5, 0.9, 1.2),
    "night_stand": (0.45, 0.55, 0.5),
    "cabinet": (0.5, 0.9, 0.9),
    "bookshelf": (0.35, 1.8, 0.9),
    "shelves": (0.35, 1.2, 0.9),
    "counter": (0.6, 0.9, 1.8),
    "lamp": (0.35, 0.55, 0.35),
    "pillow": (0.4, 0.15, 0.6),
    "television": (0.12, 0.6, 1.0),
    "toilet": (0.7, 0.75, 0.4),
    "sink": (0.5, 0.2, 0.6),
    "bathtub": (0.8, 0.55, 1.7),
    "refrigerator": (0.7, 1.8, 0.8),
    "box": (0.4, 0.3, 0.4),
    "books": (0.25, 0.25, 0.3),
    "otherfurniture": (0.6, 0.6, 0.8),
}
_DEFAULT = (0.4, 0.4, 0.4)


def typical_size(cls: str) -> tuple[float, float, float]:
    return TYPICAL_SIZE_M.get(cls, _DEFAULT)
