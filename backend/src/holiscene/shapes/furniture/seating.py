"""Seating: chair and sofa. The back is at -x: a seated person faces +x."""

from __future__ import annotations

import itertools

import numpy as np

from .. import primitives
from ..builder import ShapeBuilder, pick, vary
from .common import LegStyle, four_legs


def chair(b: ShapeBuilder, rng: np.random.Generator) -> None:
    """Four legs, a tubular sled or an office star base; a panel, slatted or ladder back;
    armrests on some. The seat height fraction sets how tall the back is."""
    base = pick(rng, ("legs", "sled", "office"), p=(0.6, 0.2, 0.2))
    seat_top = b.h * rng.uniform(0.42, 0.6)
    thick = (0.06, 0.09) if base == "office" else (0.025, 0.06)  # office seats are padded
    seat_t = vary(rng, *thick, 0.3 * seat_top)
    back_t = vary(rng, 0.025, 0.06, 0.15 * b.d)
    b.box("seat", (b.x0, b.x1), (seat_top - seat_t, seat_top), (b.z0, b.z1))

    if base == "legs":
        style: LegStyle = pick(rng, ("square", "round", "tapered"))
        thickness = vary(rng, 0.03, 0.05, 0.15 * b.d, 0.15 * b.w)
        inset = vary(rng, 0.0, 0.03, 0.1 * min(b.d, b.w))
        four_legs(b, (b.x0, b.x1), (b.z0, b.z1), (0.0, seat_top - seat_t), thickness, style, inset)
        if rng.random() < 0.4:
            _side_stretchers(b, thickness, inset, 0.25 * (seat_top - seat_t))
    elif base == "sled":
        _sled(b, seat_top - seat_t, vary(rng, 0.009, 0.014, 0.05 * b.w))
    else:
        _star_base(b, seat_top - seat_t)

    back = pick(rng, ("panel", "slats", "ladder")) if base != "office" else "office"
    _chair_back(b, rng, back, back_t, seat_top)
    arm_width = 0.0
    if rng.random() < (0.6 if base == "office" else 0.3) and b.h - seat_top > 0.1:
        arm_width = vary(rng, 0.04, 0.07, 0.15 * b.w)
        _armrests(b, rng, back_t, seat_top, arm_width)
    b.support("seat", seat_top, (b.x0 + back_t, b.x1), (b.z0 + arm_width, b.z1 - arm_width))


def _side_stretchers(b: ShapeBuilder, leg: float, inset: float, y: float) -> None:
    """Rails joining front and back legs on each side, low down."""
    rail = 0.6 * leg
    for z in (b.z0 + inset + leg / 2, b.z1 - inset - leg / 2):
        b.box(
            "stretcher",
            (b.x0 + inset + leg, b.x1 - inset - leg),
            (y - rail / 2, y + rail / 2),
            (z - rail / 2, z + rail / 2),
        )


def _sled(b: ShapeBuilder, seat_bottom: float, radius: float) -> None:
    """Tubular runners on the floor with uprights to the seat, one loop per side."""
    for z in (b.z0 + radius, b.z1 - radius):
        front, back = b.x1 - 2 * radius, b.x0 + 2 * radius
        b.add("runner", primitives.rod((b.x0, radius, z), (b.x1, radius, z), radius))
        for x in (front, back):
            b.add("runner", primitives.rod((x, radius, z), (x, seat_bottom, z), radius))


def _star_base(b: ShapeBuilder, seat_bottom: float) -> None:
    """An office chair's five-arm star on casters, and its gas-lift column."""
    caster = min(0.025, 0.1 * seat_bottom)
    arm = min(0.02, 0.1 * seat_bottom)
    arm_y = 2 * caster + arm
    column = min(0.03, 0.1 * b.d, 0.1 * b.w)
    b.add(
        "column",
        primitives.disc(
            (0.0, 0.0), (column, column), (arm_y, seat_bottom), primitives.SMALL_SECTIONS
        ),
    )
    reach_x, reach_z = b.d / 2 - caster, b.w / 2 - caster
    for k in range(5):
        angle = 2 * np.pi * k / 5
        tip = (reach_x * np.cos(angle), reach_z * np.sin(angle))
        b.add("base", primitives.rod((0.0, arm_y, 0.0), (tip[0], arm_y, tip[1]), arm))
        b.add(
            "caster",
            primitives.disc(tip, (caster, caster), (0.0, 2 * caster), primitives.SMALL_SECTIONS),
        )


def _chair_back(
    b: ShapeBuilder, rng: np.random.Generator, style: str, t: float, seat_top: float
) -> None:
    x = (b.x0, b.x0 + t)
    if style == "panel":
        b.box("back", x, (seat_top, b.h), (b.z0, b.z1))
        return
    if style == "office":
        # A padded back floating on a spine, clear of the seat.
        gap = vary(rng, 0.05, 0.12, 0.25 * (b.h - seat_top))
        spine = min(0.05, 0.15 * b.w)
        b.box("back", x, (seat_top + gap, b.h), (b.z0 + 0.05 * b.w, b.z1 - 0.05 * b.w))
        b.box("back", (b.x0, b.x0 + 0.6 * t), (seat_top, seat_top + gap), (-spine / 2, spine / 2))
        return
    stile = vary(rng, 0.025, 0.045, 0.15 * b.w)
    rail = vary(rng, 0.04, 0.09, 0.3 * (b.h - seat_top))
    for z in ((b.z0, b.z0 + stile), (b.z1 - stile, b.z1)):
        b.box("back", x, (seat_top, b.h), z)
    b.box("back", x, (b.h - rail, b.h), (b.z0 + stile, b.z1 - stile))
    inner = (b.z0 + stile, b.z1 - stile)
    if style == "slats":
        count = int(rng.integers(2, 6))
        width = min(0.03, 0.5 * (inner[1] - inner[0]) / count)
        for centre in np.linspace(inner[0], inner[1], count + 2)[1:-1]:
            b.box(
                "back",
                (x[0] + 0.2 * t, x[1] - 0.2 * t),
                (seat_top, b.h - rail),
                (centre - width / 2, centre + width / 2),
            )
    else:
        count = int(rng.integers(1, 4))
        span = b.h - rail - seat_top
        for centre in seat_top + span * np.linspace(0.35, 0.8, count):
            b.box(
                "back",
                (x[0] + 0.2 * t, x[1] - 0.2 * t),
                (centre - rail / 3, centre + rail / 3),
                inner,
            )


def _armrests(
    b: ShapeBuilder, rng: np.random.Generator, back_t: float, seat_top: float, width: float
) -> None:
    """A pad on a post at each side."""
    arm_top = seat_top + vary(rng, 0.17, 0.24, 0.6 * (b.h - seat_top))
    pad = min(0.03, 0.3 * (arm_top - seat_top))
    front = b.x1 - vary(rng, 0.0, 0.06, 0.15 * b.d)
    for z in ((b.z0, b.z0 + width), (b.z1 - width, b.z1)):
        b.box("arm", (b.x0 + back_t, front), (arm_top - pad, arm_top), z)
        b.box(
            "arm",
            (front - width, front),
            (seat_top, arm_top - pad),
            (z[0] + 0.2 * width, z[1] - 0.2 * width),
        )


def sofa(b: ShapeBuilder, rng: np.random.Generator) -> None:
    """A frame with a back and (usually) arms, a cushion per seat, back cushions, on short
    legs or a plinth. The number of seats follows the width."""
    legs = rng.random() < 0.6
    leg_h = vary(rng, 0.05, 0.14, 0.15 * b.h) if legs else 0.0
    seat_top = b.h * rng.uniform(0.45, 0.6)
    cushion_t = vary(rng, 0.1, 0.18, 0.4 * (seat_top - leg_h))
    back_t = vary(rng, 0.12, 0.25, 0.25 * b.d)
    arm_w = vary(rng, 0.1, 0.25, 0.15 * b.w) if rng.random() < 0.9 else 0.0
    arm_top = min(seat_top + rng.uniform(0.08, 0.25), b.h - 0.05 * b.h)
    # Either the back cushions stand proud of a lower frame, or the frame rises behind them.
    proud_cushions = rng.random() < 0.5
    frame_top = b.h - vary(rng, 0.0, 0.15, 0.2 * (b.h - seat_top)) if proud_cushions else b.h
    seat_z = (b.z0 + arm_w, b.z1 - arm_w)

    b.box("frame", (b.x0, b.x0 + back_t), (leg_h, frame_top), (b.z0, b.z1))
    b.box("frame", (b.x0 + back_t, b.x1), (leg_h, seat_top - cushion_t), seat_z)
    if arm_w > 0:
        for z in ((b.z0, seat_z[0]), (seat_z[1], b.z1)):
            b.box("arm", (b.x0 + back_t, b.x1), (leg_h, arm_top), z)
    if legs:
        thickness = min(0.05, 0.1 * b.d)
        per_side = 3 if b.w > 2.2 else 2
        four_legs(
            b, (b.x0, b.x1), (b.z0, b.z1), (0.0, leg_h), thickness, "square", 0.02 * b.d, per_side
        )

    seats = int(np.clip(round((seat_z[1] - seat_z[0]) / rng.uniform(0.55, 0.8)), 1, 4))
    back_cushion_t = vary(rng, 0.1, 0.18, 0.3 * (b.d - back_t))
    back_top = b.h if proud_cushions else b.h - vary(rng, 0.03, 0.1, 0.2 * (b.h - seat_top))
    edges = np.linspace(seat_z[0], seat_z[1], seats + 1)
    gap = 0.006
    for z_lo, z_hi in itertools.pairwise(edges):
        z = (float(z_lo) + gap, float(z_hi) - gap)
        b.box("cushion", (b.x0 + back_t, b.x1), (seat_top - cushion_t, seat_top), z)
        b.box(
            "back_cushion", (b.x0 + back_t, b.x0 + back_t + back_cushion_t), (seat_top, back_top), z
        )
    b.support("seat", seat_top, (b.x0 + back_t + back_cushion_t, b.x1), seat_z)
