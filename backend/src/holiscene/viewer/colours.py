"""Class colours of the viewer: the web app's palette, so a chair has one colour everywhere.

A port of `frontend/src/views/classColors.ts` (golden-angle hue steps over the NYU-40 label
order, HSL saturation 0.7, lightness 0.52). Keep the two in step. The GLB's own colours
(`export.glb.class_colour`) are a hash of the class name; the app repaints them with this
palette, and so does the viewer.
"""

from __future__ import annotations

import math

from holiscene_schema import NYU40_CLASSES

Rgb = tuple[int, int, int]

UNKNOWN_CLASS_RGB: Rgb = (128, 128, 128)
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


# Keyed by NYU-40 class name; index + 1 is the NYU-40 label id.
CLASS_RGB: dict[str, Rgb] = {
    cls: _hsl_to_rgb((index * _GOLDEN_ANGLE) % 360.0, 0.7, 0.52)
    for index, cls in enumerate(NYU40_CLASSES)
}


def class_rgb(cls: str) -> Rgb:
    return CLASS_RGB.get(cls, UNKNOWN_CLASS_RGB)
