"""The class registry: which builder makes which NYU-40 class, and how big things are."""

from __future__ import annotations

from collections.abc import Callable
from typing import NamedTuple

import numpy as np
from holiscene_schema import NYU40_CLASSES, normalise_class_name

from .builder import ShapeBuilder
from .furniture import bathroom, beds, props, seating, storage, tables, wall_items
from .shape import Shape

ShapeFn = Callable[[ShapeBuilder, np.random.Generator], None]

_BUILDERS: dict[str, ShapeFn] = {
    "bed": beds.bed,
    "chair": seating.chair,
    "sofa": seating.sofa,
    "table": tables.table,
    "desk": tables.desk,
    "dresser": storage.dresser,
    "night_stand": storage.night_stand,
    "cabinet": storage.cabinet,
    "bookshelf": storage.bookshelf,
    "shelves": storage.shelves,
    "counter": tables.counter,
    "lamp": props.lamp,
    "picture": wall_items.picture,
    "pillow": props.pillow,
    "television": wall_items.television,
    "toilet": bathroom.toilet,
    "sink": bathroom.sink,
    "bathtub": bathroom.bathtub,
    "door": wall_items.door,
    "window": wall_items.window,
    "box": props.box,
    "books": props.books,
    "mirror": wall_items.mirror,
    "curtain": wall_items.curtain,
    "refrigerator": storage.refrigerator,
}

# Classes with a parametric builder; every other NYU-40 class gets a plain box.
SUPPORTED_CLASSES: tuple[str, ...] = tuple(_BUILDERS)
GENERIC_CLASSES: tuple[str, ...] = tuple(c for c in NYU40_CLASSES if c not in _BUILDERS)

Range = tuple[float, float]


class SizeRange(NamedTuple):
    depth: Range  # x, front to back
    height: Range  # y
    width: Range  # z, side to side
    round_footprint: bool = False  # width follows depth (lamps)


# Plausible real-world sizes in metres, sampled uniformly per axis by `typical_size`.
SIZE_RANGES: dict[str, SizeRange] = {
    "bed": SizeRange((1.9, 2.2), (0.45, 1.2), (0.9, 2.0)),
    "chair": SizeRange((0.45, 0.65), (0.75, 1.1), (0.42, 0.6)),
    "sofa": SizeRange((0.8, 1.0), (0.7, 0.95), (1.4, 2.6)),
    "table": SizeRange((0.6, 1.0), (0.45, 0.78), (0.6, 1.8)),
    "desk": SizeRange((0.55, 0.8), (0.72, 0.78), (1.0, 1.8)),
    "dresser": SizeRange((0.4, 0.6), (0.7, 1.3), (0.8, 1.6)),
    "night_stand": SizeRange((0.35, 0.5), (0.45, 0.7), (0.4, 0.6)),
    "cabinet": SizeRange((0.35, 0.6), (0.6, 2.0), (0.4, 1.2)),
    "bookshelf": SizeRange((0.25, 0.4), (0.9, 2.2), (0.6, 1.2)),
    "shelves": SizeRange((0.2, 0.45), (0.4, 1.8), (0.5, 1.2)),
    "counter": SizeRange((0.55, 0.7), (0.85, 0.95), (1.0, 3.0)),
    "lamp": SizeRange((0.2, 0.5), (0.35, 1.7), (0.2, 0.5), round_footprint=True),
    "picture": SizeRange((0.02, 0.05), (0.3, 1.0), (0.3, 1.2)),
    "pillow": SizeRange((0.35, 0.5), (0.1, 0.2), (0.45, 0.75)),
    "television": SizeRange((0.05, 0.25), (0.4, 0.9), (0.6, 1.4)),
    "toilet": SizeRange((0.6, 0.75), (0.7, 0.85), (0.35, 0.45)),
    "sink": SizeRange((0.4, 0.6), (0.15, 0.95), (0.45, 0.8)),
    "bathtub": SizeRange((0.7, 0.85), (0.45, 0.65), (1.5, 1.8)),
    "door": SizeRange((0.05, 0.2), (1.95, 2.2), (0.7, 1.0)),
    "window": SizeRange((0.08, 0.3), (0.6, 1.6), (0.5, 2.0)),
    "box": SizeRange((0.2, 0.6), (0.15, 0.5), (0.2, 0.6)),
    "books": SizeRange((0.12, 0.25), (0.15, 0.3), (0.1, 0.6)),
    "mirror": SizeRange((0.02, 0.05), (0.4, 1.6), (0.3, 1.0)),
    "curtain": SizeRange((0.08, 0.2), (1.5, 2.6), (0.8, 2.5)),
    "refrigerator": SizeRange((0.6, 0.8), (1.45, 1.95), (0.55, 0.95)),
    # Generic (box-shaped) classes.
    "whiteboard": SizeRange((0.02, 0.05), (0.6, 1.2), (0.9, 2.4)),
    "blinds": SizeRange((0.03, 0.08), (0.8, 1.8), (0.6, 2.0)),
    "floor_mat": SizeRange((0.6, 2.0), (0.005, 0.02), (0.5, 3.0)),
    "clothes": SizeRange((0.2, 0.5), (0.1, 0.8), (0.3, 0.7)),
    "paper": SizeRange((0.2, 0.3), (0.001, 0.03), (0.2, 0.3)),
    "towel": SizeRange((0.03, 0.1), (0.3, 0.8), (0.3, 0.7)),
    "shower_curtain": SizeRange((0.05, 0.15), (1.6, 2.0), (0.8, 1.8)),
    "bag": SizeRange((0.15, 0.35), (0.25, 0.5), (0.3, 0.5)),
    "person": SizeRange((0.25, 0.4), (1.5, 1.9), (0.4, 0.55)),
    "otherfurniture": SizeRange((0.4, 0.9), (0.4, 1.2), (0.4, 1.2)),
    "otherprop": SizeRange((0.1, 0.4), (0.1, 0.5), (0.1, 0.4)),
    "otherstructure": SizeRange((0.2, 1.0), (0.5, 2.5), (0.2, 1.0)),
}
_DEFAULT_RANGE = SizeRange((0.3, 0.8), (0.3, 0.8), (0.3, 0.8))


def typical_size(cls: str, rng: np.random.Generator) -> tuple[float, float, float]:
    """A plausible (depth, height, width) in metres for a class (aliases accepted)."""
    ranges = SIZE_RANGES.get(normalise_class_name(cls), _DEFAULT_RANGE)
    depth = float(rng.uniform(*ranges.depth))
    height = float(rng.uniform(*ranges.height))
    width = depth if ranges.round_footprint else float(rng.uniform(*ranges.width))
    return depth, height, width


def generate_shape(cls: str, size: tuple[float, float, float], rng: np.random.Generator) -> Shape:
    """A random instance of `cls` filling the centred box of `size` = (d, h, w) exactly.

    The same rng state gives the same shape. Aliases (e.g. "nightstand", "tv") are
    normalised; a name that is not NYU-40 raises holiscene_schema.UnknownClassError.
    """
    canonical = normalise_class_name(cls)
    d, h, w = (float(s) for s in size)
    if not (d > 0 and h > 0 and w > 0 and np.isfinite([d, h, w]).all()):
        raise ValueError(f"a shape size is three positive lengths (d, h, w), got {size}")
    builder = ShapeBuilder((d, h, w))
    _BUILDERS.get(canonical, props.generic)(builder, rng)
    return builder.build()
