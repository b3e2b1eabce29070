"""The NYU-40 object vocabulary and the names other datasets use for its classes."""

from __future__ import annotations

from typing import Literal, get_args

# Canonical spellings: snake_case, "refrigerator" spelled correctly (NYU's own list has
# "refridgerator"). The order is the NYU-40 label order, so index + 1 is the NYU-40 label id.
Nyu40Class = Literal[
    "wall", "floor", "cabinet", "bed", "chair", "sofa", "table", "door", "window",
    "bookshelf", "picture", "counter", "blinds", "desk", "shelves", "curtain", "dresser",
    "pillow", "mirror", "floor_mat", "clothes", "ceiling", "books", "refrigerator",
    "television", "paper", "towel", "shower_curtain", "box", "whiteboard", "person",
    "night_stand", "toilet", "sink", "lamp", "bathtub", "bag", "otherstructure",
    "otherfurniture", "otherprop",
]  # fmt: skip

NYU40_CLASSES: tuple[str, ...] = get_args(Nyu40Class)

# Classes that are part of the room itself: they support objects and are never supported.
STRUCTURAL_CLASSES: frozenset[str] = frozenset({"wall", "floor", "ceiling"})

# Names used by SUN RGB-D, NYU v2 and Total3DUnderstanding's demo inputs, mapped to NYU-40.
# "void" marks a region of no class in SUN RGB-D; it becomes a generic prop so no box is lost.
CLASS_ALIASES: dict[str, str] = {
    "refridgerator": "refrigerator",
    "fridge": "refrigerator",
    "night_stand": "night_stand",
    "nightstand": "night_stand",
    "dresser_mirror": "mirror",
    "ottoman": "otherfurniture",
    "bookcase": "bookshelf",
    "book": "books",
    "tv": "television",
    "monitor": "television",
    "sofa_chair": "chair",
    "stool": "chair",
    "coffee_table": "table",
    "endtable": "table",
    "end_table": "table",
    "dining_table": "table",
    "garbage_bin": "otherprop",
    "recycle_bin": "otherprop",
    "plant": "otherprop",
    "laptop": "otherprop",
    "computer": "otherprop",
    "cup": "otherprop",
    "bottle": "otherprop",
    "bowl": "otherprop",
    "vase": "otherprop",
    "shelf": "shelves",
    "kitchen_counter": "counter",
    "bathroom_counter": "counter",
    "file_cabinet": "cabinet",
    "kitchen_cabinet": "cabinet",
    "bench": "otherfurniture",
    "rug": "floor_mat",
    "carpet": "floor_mat",
    "void": "otherprop",
}


class UnknownClassError(ValueError):
    """A class name that is neither NYU-40 nor a known alias of one."""


def normalise_class_name(name: str) -> str:
    """Map a dataset's class name to its NYU-40 class; raise UnknownClassError otherwise."""
    key = name.strip().lower().replace(" ", "_").replace("-", "_")
    if key in NYU40_CLASSES:
        return key
    if key in CLASS_ALIASES:
        return CLASS_ALIASES[key]
    raise UnknownClassError(
        f"unknown class name {name!r}: use an NYU-40 class (e.g. 'bed', 'night_stand') "
        "or a known SUN RGB-D alias"
    )
