"""Typical object sizes (metres) per NYU-40 class: depth (front-back), height, width.

One source of sizes: the middle of the furniture library's ranges (`shapes.SIZE_RANGES`).
"""

from __future__ import annotations

import math

from ..shapes.library import SIZE_RANGES, SizeRange

_DEFAULT = SizeRange((0.3, 0.5), (0.3, 0.5), (0.3, 0.5))


def middle_size(cls: str) -> tuple[float, float, float]:
    """(depth, height, width) at the middle of the class's ranges."""
    ranges = SIZE_RANGES.get(cls, _DEFAULT)
    depth, height, width = (sum(r) / 2 for r in (ranges.depth, ranges.height, ranges.width))
    return depth, height, width


def height_spread(cls: str) -> float:
    """Standard deviation of log(height) for the class (a uniform range's, about its middle)."""
    low, high = SIZE_RANGES.get(cls, _DEFAULT).height
    return (high - low) / ((high + low) / 2) / math.sqrt(12)


# Where people hang things on walls: the height of the lower edge above the floor (metres).
# The scene generator draws from these ranges, and the metric scale reads the typical value
# (their middle) as a measurement where a wall's floor line is known.
MOUNTING_BOTTOM_M: dict[str, tuple[float, float]] = {
    "window": (0.7, 1.0),  # sills
    "picture": (1.0, 1.6),
    "mirror": (1.0, 1.6),
    "television": (1.0, 1.6),
}


def mounting_height(cls: str) -> float | None:
    """Typical height above the floor (metres) of the lower edge of a thing hung on a wall;
    None for classes with no typical place on a wall. (A door's top is not one: its height
    is measured from the floor, with the same size prior.)"""
    low_high = MOUNTING_BOTTOM_M.get(cls)
    return None if low_high is None else sum(low_high) / 2
