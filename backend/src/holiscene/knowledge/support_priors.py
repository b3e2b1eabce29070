"""Class-level support priors: P(supporter, type | class), written down from common sense.

These are the skeleton's priors; issue 5 replaces them with priors counted from labelled scenes.
Every non-structural class falls back to the floor (furniture) or the wall (flat things).
"""

from __future__ import annotations

from typing import Literal

SupportKind = Literal["below", "behind"]
Prior = tuple[str, SupportKind, float]

_ON_WALL: list[Prior] = [("wall", "behind", 1.0)]
_ON_FLOOR: list[Prior] = [("floor", "below", 1.0)]
_SMALL_PROP: list[Prior] = [
    ("table", "below", 0.25),
    ("desk", "below", 0.2),
    ("floor", "below", 0.15),
    ("cabinet", "below", 0.1),
    ("dresser", "below", 0.1),
    ("shelves", "below", 0.1),
    ("night_stand", "below", 0.05),
    ("counter", "below", 0.05),
]

SUPPORT_PRIORS: dict[str, list[Prior]] = {
    "picture": _ON_WALL,
    "window": _ON_WALL,
    "door": _ON_WALL,
    "curtain": _ON_WALL,
    "blinds": _ON_WALL,
    "whiteboard": _ON_WALL,
    "shower_curtain": _ON_WALL,
    "mirror": [("wall", "behind", 0.7), ("dresser", "below", 0.2), ("counter", "below", 0.1)],
    "television": [
        ("wall", "behind", 0.35),
        ("cabinet", "below", 0.2),
        ("dresser", "below", 0.15),
        ("table", "below", 0.15),
        ("desk", "below", 0.15),
    ],
    "pillow": [
        ("bed", "below", 0.6),
        ("sofa", "below", 0.3),
        ("chair", "below", 0.05),
        ("floor", "below", 0.05),
    ],
    "lamp": [
        ("night_stand", "below", 0.35),
        ("table", "below", 0.25),
        ("desk", "below", 0.2),
        ("dresser", "below", 0.1),
        ("floor", "below", 0.1),
    ],
    "books": [
        ("bookshelf", "below", 0.3),
        ("shelves", "below", 0.25),
        ("desk", "below", 0.15),
        ("table", "below", 0.15),
        ("cabinet", "below", 0.05),
        ("floor", "below", 0.1),
    ],
    "box": [("floor", "below", 0.4), *[(c, t, p * 0.7) for c, t, p in _SMALL_PROP if c != "floor"]],
    "paper": [("desk", "below", 0.4), ("table", "below", 0.4), ("floor", "below", 0.2)],
    "clothes": [("bed", "below", 0.4), ("chair", "below", 0.3), ("floor", "below", 0.3)],
    "towel": [("wall", "behind", 0.5), ("counter", "below", 0.3), ("bathtub", "below", 0.2)],
    "bag": [("floor", "below", 0.6), ("chair", "below", 0.2), ("bed", "below", 0.2)],
    "sink": [("counter", "below", 0.6), ("wall", "behind", 0.4)],
    "otherprop": _SMALL_PROP,
}


def support_priors(cls: str) -> list[Prior]:
    """Candidate (supporter class or 'floor'/'wall', type, probability) for an object class."""
    return SUPPORT_PRIORS.get(cls, _ON_FLOOR)
