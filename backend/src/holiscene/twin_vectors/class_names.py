"""Test vectors for class names: `python -m holiscene.twin_vectors.class_names` writes
shared_schema/vectors/class_names.json.

A typed or imported class name is compared, and stored as an NYU-40 class, the same way on
both sides: in Python (holiscene_schema.classes: class_key, normalise_class_name) and in
TypeScript (frontend/src/state/classNames.ts: classKey, storedClass, used by the class picker
and the edit prediction). Each case is a name with its key and the class it is stored as (null:
the server refuses it). The names cover case, spaces, hyphens, repeated and outer underscores,
plurals, aliases and names no vocabulary knows, and every free name of raw_class_names.py
(SUN RGB-D-like names resolved by their words: holiscene_schema.class_words).
"""

from __future__ import annotations

import json

from holiscene_schema import UnknownClassError, class_key, normalise_class_name

from ..core.settings import REPO_ROOT
from .raw_class_names import LATER_CLASS_NAMES, RAW_CLASS_NAMES

CLASS_NAME_VECTORS = REPO_ROOT / "shared_schema" / "vectors" / "class_names.json"

NAMES = (
    "chair",
    "Chairs",
    " Night Stand ",
    "night-stand",
    "night__stand",
    "_night_stand_",
    "NIGHT - STAND",
    "night_ stand",
    "Coffee Table",
    "coffee-tables",
    "sofa",
    "couch",
    "couches",
    "TV",
    "book",
    "books",
    "bookshelf",
    "bookshelves",
    "dining table",
    "dining   table",
    "tv stand",
    "picture",
    "pictures",
    "otherprop",
    "basket",
    "baskets",
    "flux capacitor",
    "",
    "   ",
    "s",
    "(chair)",
    "of chair",
    "chair of",
    "pile of",
    "frame of",
    "tvs",
    "ies",
    "book shelf of",
)
# The free names, each once, after the cases above.
FREE_NAMES = tuple(
    dict.fromkeys(n for n, _ in (*RAW_CLASS_NAMES, *LATER_CLASS_NAMES) if n not in NAMES)
)


def class_name_vectors() -> list[dict[str, str | None]]:
    cases: list[dict[str, str | None]] = []
    for name in (*NAMES, *FREE_NAMES):
        try:
            stored: str | None = normalise_class_name(name)
        except UnknownClassError:
            stored = None
        cases.append({"name": name, "key": class_key(name), "stored": stored})
    return cases


def main() -> None:
    text = json.dumps({"cases": class_name_vectors()}, indent=1) + "\n"
    CLASS_NAME_VECTORS.write_text(text)
    print(f"wrote {CLASS_NAME_VECTORS}")


if __name__ == "__main__":
    main()
