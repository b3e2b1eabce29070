"""Test vectors for object colours: `python -m holiscene.twin_vectors.object_colours` writes
shared_schema/vectors/object_colours.json.

The scene page colours each object's mask from its id (frontend/src/views/objectColors.ts:
objectColours) and the viser viewer paints each object's mesh the same way
(holiscene.viewer.colours.object_colours), so a reviewer finds an object by its colour in
both. Each case is a scene's ids in order with the colour each gets: series of the pipeline's
and the detector's ids, more objects than the palette has slots, ids without a number, and
ids with characters beyond ASCII.
"""

from __future__ import annotations

import json
from typing import Any

from ..core.settings import REPO_ROOT
from ..viewer.colours import object_colours

OBJECT_COLOUR_VECTORS = REPO_ROOT / "shared_schema" / "vectors" / "object_colours.json"

SCENES: tuple[tuple[str, ...], ...] = (
    tuple(f"o{i}" for i in range(12)),
    ("o0", "o1", "o2", "d1", "d2", "o3_1", "floor_1"),
    tuple(f"o{i}" for i in range(40)),  # more objects than the palette's 32 slots
    ("wall", "chair-left", "Ölbild7", "椅子2", "o007", "o7"),
    ("d3", "d1", "o15", "o4", "o26"),
)


def object_colour_vectors() -> list[dict[str, Any]]:
    return [
        {"ids": list(ids), "colours": [list(rgb) for rgb in object_colours(ids).values()]}
        for ids in SCENES
    ]


def main() -> None:
    # One case per line: a scene's ids, then their colours.
    lines = [json.dumps(case, ensure_ascii=False) for case in object_colour_vectors()]
    OBJECT_COLOUR_VECTORS.write_text('{"cases": [\n' + ",\n".join(lines) + "\n]}\n")
    print(f"wrote {OBJECT_COLOUR_VECTORS}")


if __name__ == "__main__":
    main()
