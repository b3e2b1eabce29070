"""Tables and work surfaces: table, desk, counter. Each has its top as a support surface."""

from __future__ import annotations

import math

import numpy as np

from .. import primitives
from ..builder import ShapeBuilder, pick, vary
from .case import CaseRow, case
from .common import HandleStyle, LegStyle, case_base, four_legs


def _slab(
    b: ShapeBuilder, rng: np.random.Generator, low: float = 0.02, high: float = 0.05
) -> float:
    """A rectangular top over the whole footprint; returns the height of its underside."""
    under = b.h - vary(rng, low, high, 0.15 * b.h)
    b.box("top", (b.x0, b.x1), (under, b.h), (b.z0, b.z1))
    b.support("top", b.h, (b.x0, b.x1), (b.z0, b.z1))
    return under


def table(b: ShapeBuilder, rng: np.random.Generator) -> None:
    """A rectangular or round (elliptic) top on four legs (with or without an apron), a
    central pedestal, or two trestles."""
    round_top = 0.6 < b.d / b.w < 1.67 and rng.random() < 0.4
    if round_top:
        under = b.h - vary(rng, 0.025, 0.05, 0.15 * b.h)
        b.add("top", primitives.disc((0.0, 0.0), (b.d / 2, b.w / 2), (under, b.h)))
        # The largest rectangle inside the ellipse: things put there do not overhang.
        half_x, half_z = b.d / 2 / math.sqrt(2), b.w / 2 / math.sqrt(2)
        b.support("top", b.h, (-half_x, half_x), (-half_z, half_z))
        base = pick(rng, ("legs", "pedestal"), p=(0.4, 0.6))
    else:
        under = _slab(b, rng, 0.025, 0.05)
        base = pick(rng, ("legs", "pedestal", "trestle"), p=(0.65, 0.15, 0.2))

    span = min(b.d, b.w)
    if base == "legs":
        style: LegStyle = pick(rng, ("square", "round", "tapered"))
        thickness = vary(rng, 0.04, 0.08, 0.12 * span)
        if round_top:
            x, z, inset = (-0.32 * b.d, 0.32 * b.d), (-0.32 * b.w, 0.32 * b.w), 0.0
        else:
            x, z, inset = (b.x0, b.x1), (b.z0, b.z1), vary(rng, 0.02, 0.08, 0.1 * span)
        four_legs(b, x, z, (0.0, under), thickness, style, inset)
        if not round_top and rng.random() < 0.6:
            _apron(b, x, z, inset + 0.2 * thickness, under, vary(rng, 0.06, 0.1, 0.2 * under))
    elif base == "pedestal":
        column = vary(rng, 0.04, 0.08, 0.15 * span)
        foot_t = vary(rng, 0.02, 0.05, 0.1 * under)
        b.add(
            "base",
            primitives.disc(
                (0.0, 0.0), (column, column), (foot_t, under), primitives.SMALL_SECTIONS
            ),
        )
        reach = rng.uniform(0.25, 0.4)
        if rng.random() < 0.5:
            b.add("base", primitives.disc((0.0, 0.0), (reach * b.d, reach * b.w), (0.0, foot_t)))
        else:
            # A cross of two feet.
            b.box("base", (-reach * b.d, reach * b.d), (0.0, foot_t), (-column, column))
            b.box("base", (-column, column), (0.0, foot_t), (-reach * b.w, reach * b.w))
    else:
        _trestles(b, rng, under)


def _apron(
    b: ShapeBuilder,
    x: tuple[float, float],
    z: tuple[float, float],
    inset: float,
    under: float,
    height: float,
) -> None:
    """Boards under the top joining the legs."""
    thickness = min(0.02, 0.05 * min(b.d, b.w))
    y = (under - height, under)
    xi, zi = (x[0] + inset, x[1] - inset), (z[0] + inset, z[1] - inset)
    b.box("apron", xi, y, (zi[0], zi[0] + thickness))
    b.box("apron", xi, y, (zi[1] - thickness, zi[1]))
    b.box("apron", (xi[0], xi[0] + thickness), y, (zi[0] + thickness, zi[1] - thickness))
    b.box("apron", (xi[1] - thickness, xi[1]), y, (zi[0] + thickness, zi[1] - thickness))


def _trestles(b: ShapeBuilder, rng: np.random.Generator, under: float) -> None:
    """An upright and a foot at each end (along z), joined by a stretcher."""
    thickness = vary(rng, 0.04, 0.07, 0.1 * b.w)
    foot = vary(rng, 0.04, 0.07, 0.15 * under)
    inset = vary(rng, 0.05, 0.15, 0.15 * b.w)
    for z in (b.z0 + inset, b.z1 - inset - thickness):
        b.box("base", (-0.3 * b.d, 0.3 * b.d), (foot, under), (z, z + thickness))
        b.box(
            "base",
            (-0.42 * b.d, 0.42 * b.d),
            (0.0, foot),
            (z - 0.5 * thickness, z + 1.5 * thickness),
        )
    y = rng.uniform(0.3, 0.6) * under
    b.box(
        "stretcher",
        (-thickness / 2, thickness / 2),
        (y - thickness, y),
        (b.z0 + inset + thickness, b.z1 - inset - thickness),
    )


def desk(b: ShapeBuilder, rng: np.random.Generator) -> None:
    """A top on four legs, on two side panels, or on a drawer pedestal and a panel; the
    user sits at +x, a modesty panel closes the back on some."""
    under = _slab(b, rng, 0.02, 0.04)
    style = pick(rng, ("legs", "panels", "pedestal"))
    panel = vary(rng, 0.018, 0.035, 0.05 * b.w)
    recess = vary(rng, 0.0, 0.05, 0.1 * b.d)
    if style == "legs":
        thickness = vary(rng, 0.035, 0.06, 0.1 * min(b.d, b.w))
        four_legs(
            b,
            (b.x0, b.x1),
            (b.z0, b.z1),
            (0.0, under),
            thickness,
            pick(rng, ("square", "round")),
            0.02 * b.w,
        )
        sides = (b.z0 + 0.02 * b.w + thickness, b.z1 - 0.02 * b.w - thickness)
    elif style == "panels":
        for z in ((b.z0, b.z0 + panel), (b.z1 - panel, b.z1)):
            b.box("side", (b.x0, b.x1 - recess), (0.0, under), z)
        sides = (b.z0 + panel, b.z1 - panel)
    else:
        # A drawer pedestal on one side, a panel on the other.
        width = vary(rng, 0.35, 0.45, 0.45 * b.w)
        left = rng.random() < 0.5
        z = (b.z0, b.z0 + width) if left else (b.z1 - width, b.z1)
        other = (b.z1 - panel, b.z1) if left else (b.z0, b.z0 + panel)
        rows = [CaseRow("drawer") for _ in range(int(np.clip(under // 0.18, 1, 4)))]
        handles: HandleStyle = pick(rng, ("bar", "knob"))
        case(b, (b.x0, b.x1 - recess), (0.0, under), z, rows, rng, handle_style=handles)
        b.box("side", (b.x0, b.x1 - recess), (0.0, under), other)
        sides = (z[1], other[0]) if left else (other[1], z[0])
    if rng.random() < 0.6:
        low = under * rng.uniform(0.35, 0.6)
        b.box("modesty_panel", (b.x0 + 0.02 * b.d, b.x0 + 0.02 * b.d + panel), (low, under), sides)


def counter(b: ShapeBuilder, rng: np.random.Generator) -> None:
    """Base cabinets on a toe kick under an overhanging worktop, maybe a backsplash."""
    splash_h = vary(rng, 0.05, 0.15, 0.15 * b.h) if rng.random() < 0.3 else 0.0
    splash_t = min(0.02, 0.05 * b.d) if splash_h else 0.0
    top_t = vary(rng, 0.02, 0.05, 0.1 * b.h)
    worktop = b.h - splash_h
    under = worktop - top_t
    overhang = vary(rng, 0.01, 0.04, 0.1 * b.d)
    b.box("top", (b.x0, b.x1), (under, worktop), (b.z0, b.z1))
    if splash_h:
        b.box("backsplash", (b.x0, b.x0 + splash_t), (worktop, b.h), (b.z0, b.z1))
    b.support("top", worktop, (b.x0 + splash_t, b.x1), (b.z0, b.z1))

    x = (b.x0, b.x1 - overhang)
    bottom = case_base(b, x, (b.z0, b.z1), "plinth", rng)
    columns = int(np.clip(round(b.w / rng.uniform(0.45, 0.65)), 1, 8))
    layout = pick(rng, ("doors_drawers", "doors", "drawers"), p=(0.5, 0.3, 0.2))
    rows = {
        "doors_drawers": [CaseRow("door", columns), CaseRow("drawer", columns, weight=0.3)],
        "doors": [CaseRow("door", columns)],
        "drawers": [CaseRow("drawer", columns) for _ in range(3)],
    }[layout]
    handles: HandleStyle = pick(rng, ("bar", "knob", "none"), p=(0.5, 0.3, 0.2))
    case(b, x, (bottom, under), (b.z0, b.z1), rows, rng, handle_style=handles)
