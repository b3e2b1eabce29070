"""Colours of the viewer: the web app's palette, so an object looks the same in both.

Objects are coloured by object, as the scene page colours their masks by default: a port of
`frontend/src/views/objectColors.ts` (`objectColours`), held to it by
shared_schema/vectors/object_colours.json. The GLB's own colours
(`export.glb.class_colour`) are a hash of the class name; the app repaints them with this
palette, and so does the viewer.
"""

from __future__ import annotations

import math
import re
from collections.abc import Sequence

Rgb = tuple[int, int, int]

_GOLDEN_ANGLE = 137.508


def _js_round(value: float) -> int:
    # JavaScript's Math.round (halves up), not Python's round-half-to-even.
    return math.floor(value + 0.5)


def _hsl_to_rgb(h: float, s: float, lightness: float) -> Rgb:
    a = s * min(lightness, 1.0 - lightness)

    def channel(n: int) -> int:
        k = (n + h / 30.0) % 12.0
        return _js_round(255.0 * (lightness - a * max(-1.0, min(k - 3.0, 9.0 - k, 1.0))))

    return channel(0), channel(8), channel(4)


# The per-object palette: 32 slots, consecutive ones far apart in hue, two lightnesses.
_OBJECT_LIGHTNESS = (0.55, 0.38)
_SLOTS = 32


def _slot_hue(k: int) -> float:
    return (k * _GOLDEN_ANGLE) % 360.0


OBJECT_PALETTE: tuple[Rgb, ...] = tuple(
    _hsl_to_rgb(_slot_hue(k), 0.8, _OBJECT_LIGHTNESS[k % 2]) for k in range(_SLOTS)
)
# Two colours nearer in hue read as one (a darker red is still red).
_NEAR_HUE = 25.0


def _hue_distance(a: int, b: int) -> float:
    d = abs(_slot_hue(a) - _slot_hue(b))
    return min(d, 360.0 - d)


def _nearest_given(k: int, given: set[int]) -> float:
    return min((_hue_distance(k, g) for g in given), default=360.0)


_NUMBERED = re.compile(r"^(.*?)([0-9]+)$")  # ASCII digits, as JavaScript's \d


def _id_hash(text: str) -> int:
    """FNV-1a over the UTF-16 code units, as JavaScript's charCodeAt sees a string."""
    units = text.encode("utf-16-le")
    value = 0x811C9DC5
    for i in range(0, len(units), 2):
        value ^= units[i] | (units[i + 1] << 8)
        value = (value * 0x01000193) & 0xFFFFFFFF
    return value


def _preferred_slot(object_id: str) -> int:
    """Ids in a series ("o0", "o1", ...) take consecutive slots, far apart in hue."""
    numbered = _NUMBERED.match(object_id)
    if numbered is None:
        return _id_hash(object_id) % len(OBJECT_PALETTE)
    return (_id_hash(numbered.group(1)) + int(numbered.group(2))) % len(OBJECT_PALETTE)


def object_colours(ids: Sequence[str]) -> dict[str, Rgb]:
    """Each object's colour, in the scene's order: its id's slot, unless an earlier object has
    that slot or one of a near hue; then the free slot farthest in hue from every slot given
    (the lowest of equals). Past 32 objects, slots are shared."""
    used: set[int] = set()
    colours: dict[str, Rgb] = {}
    for object_id in ids:
        slot = _preferred_slot(object_id)
        if slot in used or _nearest_given(slot, used) < _NEAR_HUE:
            best = -1.0
            for k in range(_SLOTS):
                distance = _nearest_given(k, used) if k not in used else -1.0
                if distance > best:
                    best, slot = distance, k
        used.add(slot)
        colours[object_id] = OBJECT_PALETTE[slot]
    return colours
