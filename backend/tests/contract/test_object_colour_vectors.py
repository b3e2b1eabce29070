"""The object-colour vectors (shared_schema/vectors/object_colours.json) are what the viewer
computes now: the scene page's twin (frontend/src/views/objectColors.ts) is tested against the
same file, so an object has one colour on the page and in viser."""

from __future__ import annotations

import json

from holiscene.twin_vectors.object_colours import OBJECT_COLOUR_VECTORS, object_colour_vectors
from holiscene.viewer.colours import OBJECT_PALETTE, object_colours


def test_the_vectors_are_current() -> None:
    stored = json.loads(OBJECT_COLOUR_VECTORS.read_text())["cases"]
    assert stored == object_colour_vectors(), (
        "run `python -m holiscene.twin_vectors.object_colours` and commit the file"
    )


def test_objects_of_a_scene_differ_until_the_palette_runs_out() -> None:
    ids = [f"o{i}" for i in range(len(OBJECT_PALETTE))]
    assert len(set(object_colours(ids).values())) == len(OBJECT_PALETTE)
    # Consecutive pipeline ids take consecutive slots: far apart in hue.
    first = object_colours(["o0", "o1"])
    assert first["o0"] != first["o1"]
    # An object keeps its colour when one is added after it.
    assert object_colours(["o0", "o1", "d1"])["o1"] == first["o1"]
