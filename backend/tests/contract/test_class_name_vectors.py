"""The class-name vectors (shared_schema/vectors/class_names.json) are what the contract
computes now: the TypeScript twin (frontend/src/state/classNames.ts) is tested against the same
file, so both sides key and store every name alike."""

from __future__ import annotations

import json

from holiscene.twin_vectors.class_names import CLASS_NAME_VECTORS, class_name_vectors


def test_the_vectors_are_current() -> None:
    stored = json.loads(CLASS_NAME_VECTORS.read_text())["cases"]
    assert stored == class_name_vectors(), (
        "run `python -m holiscene.twin_vectors.class_names` and commit the file"
    )


def test_the_vectors_cover_refused_plural_and_alias_names() -> None:
    cases = {c["name"]: c["stored"] for c in class_name_vectors()}
    assert cases["couches"] == "sofa"  # an alias's plural
    assert cases["night__stand"] == "night_stand"  # repeated underscores collapse
    assert cases["flux capacitor"] is None  # refused by the strict lookup
