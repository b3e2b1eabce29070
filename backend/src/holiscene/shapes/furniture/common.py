"""Sub-assemblies shared across families: legs, bases, handles and frames."""

from __future__ import annotations

from typing import Literal

import numpy as np

from .. import primitives
from ..builder import ShapeBuilder, vary
from ..shape import Interval

LegStyle = Literal["square", "round", "tapered"]
HandleStyle = Literal["bar", "knob", "none"]
BaseStyle = Literal["plinth", "legs", "none"]


def corner_points(
    x: Interval, z: Interval, inset: float, per_side: int = 2
) -> list[tuple[float, float]]:
    """Leg centres: `per_side` along each long (x) side, `inset` in from the rectangle."""
    xs = np.linspace(x[0] + inset, x[1] - inset, per_side)
    return [(float(px), pz) for px in xs for pz in (z[0] + inset, z[1] - inset)]


def leg(
    b: ShapeBuilder, centre: tuple[float, float], y: Interval, thickness: float, style: LegStyle
) -> None:
    cx, cz = centre
    r = thickness / 2.0
    if style == "round":
        b.add("leg", primitives.disc(centre, (r, r), y, primitives.SMALL_SECTIONS))
    elif style == "tapered":
        # Thinner at the floor, as on mid-century tables.
        foot = (r * 0.55, r * 0.55)
        bottom = [(cx - foot[0], cx + foot[0]), (cz - foot[1], cz + foot[1])]
        b.add("leg", primitives.tapered_box(1, y, bottom, [(cx - r, cx + r), (cz - r, cz + r)]))
    else:
        b.box("leg", (cx - r, cx + r), y, (cz - r, cz + r))


def four_legs(
    b: ShapeBuilder,
    x: Interval,
    z: Interval,
    y: Interval,
    thickness: float,
    style: LegStyle,
    inset: float = 0.0,
    per_side: int = 2,
) -> None:
    """Legs under the rectangle x by z, their outer faces `inset` in from its edges."""
    for centre in corner_points(x, z, inset + thickness / 2.0, per_side):
        leg(b, centre, y, thickness, style)


def case_base(
    b: ShapeBuilder, x: Interval, z: Interval, style: BaseStyle, rng: np.random.Generator
) -> float:
    """What a cabinet stands on; returns the height of the carcass bottom."""
    if style == "none":
        return 0.0
    height = vary(rng, 0.06, 0.14, 0.2 * b.h)
    if style == "plinth":
        # A toe-kick: set back at the front so the fronts overhang it.
        recess = min(0.06, 0.15 * (x[1] - x[0]))
        b.box(
            "plinth", (x[0], x[1] - recess), (0.0, height), (z[0] + 0.01 * b.w, z[1] - 0.01 * b.w)
        )
    else:
        thickness = min(0.045, 0.15 * (x[1] - x[0]), 0.15 * (z[1] - z[0]))
        four_legs(b, x, z, (0.0, height), thickness, "square", inset=0.01 * b.w)
    return height


def handle(
    b: ShapeBuilder,
    x: Interval,
    y: float,
    z: float,
    length: float,
    vertical: bool,
    style: HandleStyle,
    front: float,
) -> None:
    """A pull on a front: `x` runs from the front's face to the tip of the handle.

    `front` is the smaller side of the front it is on: a knob or bar stays well inside it.
    """
    depth = x[1] - x[0]
    if style == "none" or depth <= 0:
        return
    if style == "knob":
        radius = min(0.018, 0.8 * depth, 0.3 * front)
        b.add("handle", primitives.rod((x[0], y, z), (x[1], y, z), radius))
        return
    bar = min(0.012, 0.5 * depth, 0.15 * front)
    if vertical:
        b.box("handle", x, (y - length / 2, y + length / 2), (z - bar, z + bar))
    else:
        b.box("handle", x, (y - bar, y + bar), (z - length / 2, z + length / 2))


def frame(
    b: ShapeBuilder,
    name: str,
    x: Interval,
    y: Interval,
    z: Interval,
    width: float,
    bottom: bool = True,
) -> tuple[Interval, Interval]:
    """A rectangular frame of bars `width` wide; returns the opening (y, z) it leaves.

    Without `bottom` the sides reach the floor, as a door's jambs do.
    """
    y_in = (y[0] + width if bottom else y[0], y[1] - width)
    b.box(name, x, (y_in[1], y[1]), z)
    if bottom:
        b.box(name, x, (y[0], y_in[0]), z)
    b.box(name, x, y_in, (z[0], z[0] + width))
    b.box(name, x, y_in, (z[1] - width, z[1]))
    return y_in, (z[0] + width, z[1] - width)
