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
