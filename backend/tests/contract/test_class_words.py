"""Free class names (SUN RGB-D's typed names) resolved by their words: the steps of
holiscene_schema.class_words one by one, and the hand-written raw names with their NYU-40
classes (twin_vectors/raw_class_names.py), which the import and the class picker map alike."""

from __future__ import annotations

import json

import pytest
from holiscene.inputs import parse_detections
from holiscene.pipeline.stages.detections import unknown_class_note
from holiscene.twin_vectors.raw_class_names import (
    KNOWN_MISSES,
    LATER_CLASS_NAMES,
    RAW_CLASS_NAMES,
    misses,
    tally,
)
from holiscene_schema import (
    NYU40_CLASSES,
    UnknownClassError,
    map_class_name,
    normalise_class_name,
)
from holiscene_schema.class_words import class_words, resolve_words, singular, typo_fixes
from holiscene_schema.classes import CLASS_ALIASES


@pytest.mark.parametrize(
    ("name", "words"),
    [
        ("Chair#3", ["chair"]),
        ("office_chair-2", ["office", "chair"]),
        ("pillow(s)", ["pillow"]),
        ("chair (broken) 2", ["chair"]),
        ("person's bag", ["person", "s", "bag"]),
        ("  ", []),
    ],
)
def test_a_name_is_read_as_its_words(name: str, words: list[str]) -> None:
    assert class_words(name) == words


@pytest.mark.parametrize(
    ("word", "expected"),
    [
        ("chairs", "chair"), ("couches", "couch"), ("boxes", "box"), ("glasses", "glass"),
        ("batteries", "battery"), ("shelves", "shelf"), ("people", "person"), ("tvs", "tv"),
        ("glass", "glass"), ("bus", "bus"), ("chair", "chair"), ("shoes", "shoe"),
    ],
)  # fmt: skip
def test_singular(word: str, expected: str) -> None:
    assert singular(word) == expected


@pytest.mark.parametrize(
    ("name", "expected"),
    [
        ("book shelf", "bookshelf"),  # joined: the alias "bookshelf"
        ("coffeetable", "table"),  # coffee_table without its "_"
        ("small kitchen cabinet", "cabinet"),  # the longest known tail
        ("office chair", "chair"),
        ("bed frame", "bed"),  # a generic head: the modifiers first
        ("frame", "picture"),  # ... and alone, its own class
        ("pile of books", "books"),  # "X of Y" with X generic: Y
        ("chest of drawers", "dresser"),  # a whole alias before "of"
        ("lamp on table", "lamp"),  # "X on Y": X
        ("tv remote", "otherprop"),  # the head, not the modifier
        ("chiar", "chair"),  # neighbours swapped
        ("pilow", "pillow"),  # a letter missing
        ("cabinent", "cabinet"),  # a letter too many, in a long word
        ("shelvs", "shelves"),  # a typo in a plural
    ],
)
def test_free_names_resolve_by_their_words(name: str, expected: str) -> None:
    assert normalise_class_name(name) == expected
    assert map_class_name(name).known


@pytest.mark.parametrize(
    "name", ["flux capacitor", "cable", "tablet", "hair", "sheet", "door knob", "", "of"]
)
def test_names_without_a_known_head_stay_unknown(name: str) -> None:
    """A letter typed for another is not fixed ("cable" is no table), a short word is never
    fixed ("hair" is no chair), and an unknown head is not guessed from its modifiers."""
    with pytest.raises(UnknownClassError):
        normalise_class_name(name)
    mapped = map_class_name(name)
    assert (mapped.cls, mapped.known) == ("otherprop", False)


def test_a_typo_is_fixed_only_to_one_class() -> None:
    assert typo_fixes("sotol", {"stool", "stole"}) == ["stool"]
    assert typo_fixes("stoo", {"stool"}) == []  # too short to fix
    # "acbde": "abcde" with two letters swapped, or "acbdex" with its last letter missing.
    classes = {"abcde": "chair", "acbdex": "table"}
    assert resolve_words(["acbde"], classes.get, classes) is None
    classes["acbdex"] = "chair"
    assert resolve_words(["acbde"], classes.get, classes) == "chair"


def test_joined_keys_do_not_clash() -> None:
    """A key without its "_" names one class (a clash would make the joined form ambiguous)."""
    joined: dict[str, set[str]] = {}
    for key, cls in [*((c, c) for c in NYU40_CLASSES), *CLASS_ALIASES.items()]:
        joined.setdefault(key.replace("_", ""), set()).add(cls)
    assert {k: v for k, v in joined.items() if len(v) > 1} == {}


def test_the_raw_names_map_to_their_classes_but_the_known_misses() -> None:
    assert len(RAW_CLASS_NAMES) + len(LATER_CLASS_NAMES) >= 150
    missed = {name for name, _, _ in misses(RAW_CLASS_NAMES) + misses(LATER_CLASS_NAMES)}
    assert missed == KNOWN_MISSES
    first, later = tally(RAW_CLASS_NAMES), tally(LATER_CLASS_NAMES)
    assert first["specific right"] / first["specific"] > 0.985
    assert later["specific right"] / later["specific"] > 0.93
    assert first["wrong class"] + later["wrong class"] == 2  # box of tissues, cabinet_door


def test_an_import_keeps_the_typed_name_and_warns_for_none_of_these() -> None:
    items = [{"bbox": [0, 0, 10, 10], "class": n} for n in ("office chair", "chair 2", "chiar")]
    detections = parse_detections(json.dumps(items).encode(), 64, 48)
    assert [(d.cls, d.source_class, d.class_known) for d in detections] == [
        ("chair", "office chair", True),
        ("chair", "chair 2", True),
        ("chair", "chiar", True),
    ]
    assert unknown_class_note(detections) is None
