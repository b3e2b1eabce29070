"""The NYU-40 object vocabulary and the names other datasets use for its classes."""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass
from typing import Literal, get_args

from .class_words import class_words, resolve_words

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

# Names used by SUN RGB-D, NYU v2, COCO-style lists and Total3DUnderstanding's demo inputs,
# mapped to NYU-40 (docs/importing.md), and synonyms of indoor object words. "void" marks a
# region of no class in SUN RGB-D; it becomes a generic prop so no box is lost. A name found
# nowhere here is resolved by its words (class_words.py: "office chair" is a chair), else
# becomes `otherprop` on import, with the name kept (map_class_name); a user's class map
# overrides all of these. ("dress" is no alias: typed in the class picker it would come
# before "dresser".) NYU-40's meaning decides: a sofa chair (an armchair) is a chair, a
# sofa bed a sofa (how it stands in a room), a mattress or headboard the bed it belongs to;
# whole names are listed where the head word says the wrong thing ("toilet seat" is the
# toilet, "cutting board" and "hair dryer" are props, "table cloth" is no clothes). Where
# NYU's own 894-name mapping and ScanNet's agree on a word's class, it is theirs: lights and
# boards other than whiteboards are structure, bins for waste and radiators furniture.
_ALIASES_BY_CLASS: dict[str, tuple[str, ...]] = {
    "cabinet": (
        "cabinets", "cupboard", "file_cabinet", "filing_cabinet", "kitchen_cabinet",
        "kitchen_cabinets", "bathroom_cabinet", "wall_cabinet", "tv_cabinet", "locker",
    ),
    "bed": (
        "double_bed", "single_bed", "bunk_bed", "twin_bed", "queen_bed", "king_bed", "mattress",
        "headboard", "footboard", "bed_frame",
    ),
    "chair": (
        "armchair", "arm_chair", "office_chair", "desk_chair", "dining_chair", "stool",
        "bar_stool", "sofa_chair", "rocking_chair", "folding_chair", "high_chair", "seat",
        "recliner", "wheelchair", "beanbag", "bean_bag",
    ),
    "sofa": (
        "couch", "loveseat", "love_seat", "sectional", "sectional_sofa", "futon", "settee",
        "sofa_bed", "divan", "chesterfield",
    ),
    "table": (
        "coffee_table", "endtable", "end_table", "side_table", "dining_table", "kitchen_table",
        "round_table", "conference_table", "folding_table", "tea_table", "console_table",
        "dinning_table",
    ),
    "door": ("doors", "closet_door", "sliding_door", "glass_door", "door_frame"),
    "window": ("windows", "window_frame", "skylight"),
    "bookshelf": ("bookcase", "book_shelf", "bookshelves", "book_case"),
    "picture": (
        "pictures", "painting", "poster", "photo", "photograph", "picture_frame", "frame",
        "framed_picture", "artwork", "wall_art",
    ),
    "counter": ("kitchen_counter", "bathroom_counter", "countertop", "kitchen_island", "island"),
    "blinds": ("blind", "window_blind", "window_blinds", "window_shade", "shade", "shades"),
    "desk": ("computer_desk", "office_desk", "writing_desk", "study_desk"),
    "shelves": ("shelf", "wall_shelf", "shelving", "rack_shelf"),
    "curtain": ("curtains", "drape", "drapes", "drapery"),
    "dresser": ("chest_of_drawers", "drawers", "drawer", "chest", "bureau", "vanity"),
    "pillow": ("pillows", "cushion", "cushions", "throw_pillow", "sofa_pillow"),
    "mirror": ("dresser_mirror", "bathroom_mirror", "wall_mirror", "mirrors"),
    "floor_mat": ("mat", "rug", "carpet", "bath_mat", "doormat", "door_mat", "floor_rug"),
    "clothes": (
        "clothing", "cloth", "shirt", "jacket", "coat", "pants", "jeans", "sweater",
        "skirt", "trousers", "shorts", "hoodie", "blouse", "scarf", "sock", "socks", "garment",
        "laundry",
    ),
    "books": ("book", "notebook", "magazine", "magazines", "binder", "folder"),
    "refrigerator": ("refridgerator", "fridge", "mini_fridge", "freezer"),
    "television": (
        "tv", "monitor", "computer_monitor", "screen", "tv_screen", "television_set",
        "flat_screen_tv", "telly", "flatscreen",
    ),
    "paper": ("papers", "newspaper", "document", "documents", "envelope"),
    "towel": ("towels", "hand_towel", "bath_towel", "paper_towel"),
    "shower_curtain": ("shower_curtains",),
    "box": ("boxes", "cardboard_box", "carton", "storage_box", "shoe_box", "package", "mailbox"),
    "whiteboard": ("white_board", "dry_erase_board"),
    "person": (
        "people", "man", "woman", "child", "boy", "girl", "human", "baby", "kid", "adult",
        "student", "lady", "guy",
    ),
    "night_stand": ("nightstand", "night_table", "bedside_table", "bed_side_table"),
    "toilet": ("toilets", "urinal", "toilet_seat", "toilet_bowl", "toilet_tank", "commode"),
    "sink": ("sinks", "bathroom_sink", "kitchen_sink", "basin", "wash_basin"),
    "lamp": (
        "lamps", "table_lamp", "floor_lamp", "desk_lamp", "bedside_lamp", "lampshade",
        "desk_light", "night_light", "reading_light",
    ),
    "bathtub": ("bath_tub", "tub", "bath"),
    "bag": ("bags", "backpack", "handbag", "purse", "suitcase", "luggage", "paper_bag"),
    "otherstructure": (
        "column", "pillar", "beam", "stairs", "staircase", "stair", "railing", "fireplace",
        "vent", "duct", "pipe", "ledge", "step", "light", "ceiling_light", "chandelier",
        "board", "bulletin_board", "blackboard", "chalkboard", "projector_screen", "mantel",
        "mantle", "banister", "chimney", "gate", "light_switch", "range_hood", "curtain_rod",
        "towel_rod", "rail", "handrail", "grab_bar", "windowsill", "window_sill", "stall",
        "shower_stall",
    ),
    "otherfurniture": (
        "ottoman", "bench", "piano", "stand", "tv_stand", "rack", "coat_rack", "cart",
        "ironing_board", "footstool", "crib", "wardrobe", "closet", "armoire", "sideboard",
        "hutch", "stove", "oven", "dishwasher", "washing_machine", "dryer", "radiator",
        "trash_can", "trash_bin", "garbage_bin", "garbage_can", "recycle_bin", "recycling_bin",
        "waste_bin", "ladder", "stepladder", "crate", "stroller", "cradle", "bassinet",
        "treadmill", "furnace",
    ),
    "otherprop": (
        "void", "basket", "bin", "wastebasket", "clock", "fan", "plant", "potted_plant",
        "flower", "flowers", "vase", "laptop", "computer", "keyboard", "mouse", "speaker",
        "printer", "phone", "telephone", "remote", "remote_control", "cup", "mug", "glass",
        "bottle", "bowl", "plate", "jar", "can", "pot", "pan", "kettle", "microwave", "toaster",
        "candle", "toy", "stuffed_animal", "tissue_box", "soap", "cellphone", "cell_phone",
        "container", "tray", "decoration", "ornament", "statue", "sculpture", "globe",
        "umbrella", "shoe", "shoes", "hat", "blanket", "scissors", "pen", "pencil", "glasses",
        "toilet_paper", "cutting_board", "chopping_board", "hair_dryer", "table_cloth",
        "tablecloth", "holder", "dispenser", "quilt", "comforter", "duvet", "bedspread",
        "tv_remote", "projector", "heater", "air_conditioner",
    ),
}  # fmt: skip

CLASS_ALIASES: dict[str, str] = {
    alias: cls for cls, aliases in _ALIASES_BY_CLASS.items() for alias in aliases
}

# What a name found nowhere becomes on import (its own name is kept as `source_class`).
UNKNOWN_CLASS_FALLBACK = "otherprop"


# Every key with its `_` left out too ("coffee_table" as "coffeetable", "book_shelf" as
# "bookshelf"), for names typed joined; one class each (class_words.py, step 1).
_JOINED_KEYS: dict[str, str] = {
    key.replace("_", ""): cls
    for key, cls in [*((c, c) for c in NYU40_CLASSES), *CLASS_ALIASES.items()]
}
# The one-word keys: the words a typo in a name may be fixed to (class_words.py, step 4).
_KNOWN_WORDS: frozenset[str] = frozenset(
    key for key in (*NYU40_CLASSES, *CLASS_ALIASES) if "_" not in key
)


def _known_key(key: str) -> str | None:
    """The class of a vocabulary key (a class, an alias, or either without its `_`)."""
    if key in NYU40_CLASSES:
        return key
    return CLASS_ALIASES.get(key) or _JOINED_KEYS.get(key)


class UnknownClassError(ValueError):
    """A class name that is neither NYU-40 nor a known alias of one."""


def class_key(name: str) -> str:
    """A name as the lookups compare it: trimmed, lower case, words joined by `_`."""
    return "_".join(name.strip().lower().replace("-", " ").replace("_", " ").split())


def normalise_class_name(name: str) -> str:
    """Map a dataset's class name to its NYU-40 class; raise UnknownClassError otherwise.
    A plural of a known name ("chairs", "couches") is known too, and a free name is resolved
    by its words (class_words.py: "office chair", "book shelf", "chair 2", "chiar")."""
    key = class_key(name)
    plurals = (key[:-1] if key.endswith("s") else None, key[:-2] if key.endswith("es") else None)
    for candidate in (key, *plurals):
        if candidate in NYU40_CLASSES:
            return candidate
        if candidate in CLASS_ALIASES:
            return CLASS_ALIASES[candidate]
    resolved = resolve_words(class_words(name), _known_key, _KNOWN_WORDS)
    if resolved is not None:
        return resolved
    raise UnknownClassError(
        f"unknown class name {name!r}: use an NYU-40 class (e.g. 'bed', 'night_stand') "
        "or a known SUN RGB-D alias"
    )


@dataclass(frozen=True)
class ClassMapping:
    cls: str
    known: bool  # False: the name was found nowhere and became UNKNOWN_CLASS_FALLBACK


def map_class_name(name: str, class_map: Mapping[str, str] | None = None) -> ClassMapping:
    """An imported name's NYU-40 class: the user's class map first (keys compared as
    class_key does, values NYU-40 names), then NYU-40 and its aliases, else `otherprop`
    (known=False), so one odd name never refuses a whole file."""
    key = class_key(name)
    if class_map and key in class_map:
        return ClassMapping(class_map[key], True)
    try:
        return ClassMapping(normalise_class_name(name), True)
    except UnknownClassError:
        return ClassMapping(UNKNOWN_CLASS_FALLBACK, False)
