"""Bathroom fixtures: toilet, sink, bathtub. Simple, but each with its telltale part: a
toilet's tank at the back (-x), a sink's faucet behind its basin, a bathtub's hollow."""

from __future__ import annotations

import numpy as np

from .. import primitives
from ..builder import ShapeBuilder, pick, vary
from .case import CaseRow, case
from .common import case_base


def _bowl_profile(
    y: tuple[float, float], outer_bottom: float, wall: float, inner_bottom: float, depth: float
) -> list[tuple[float, float]]:
    """A closed half cross-section of a hollow bowl: the outside from its bottom (radius
    `outer_bottom`) up to the rim (radius 1), then down the inside (`wall` thick at the rim,
    radius `inner_bottom` at the bottom, `depth` metres deep). Radii are relative."""
    return [
        (0.0, y[0]),
        (outer_bottom, y[0]),
        (1.0, y[1]),
        (1.0 - wall, y[1]),
        (inner_bottom, y[1] - depth),
        (0.0, y[1] - depth),
    ]


def toilet(b: ShapeBuilder, rng: np.random.Generator) -> None:
    """A tank with a lid against the wall, a bowl on a foot, a seat ring and a lid, closed
    or standing up against the tank."""
    tank_d = vary(rng, 0.14, 0.22, 0.35 * b.d)
    lid_t = min(0.025, 0.05 * b.h)
    seat_y = b.h * rng.uniform(0.5, 0.62)
    seat_t = min(0.03, 0.06 * b.h)
    tank_bottom = min(seat_y * rng.uniform(0.8, 1.0), b.h - lid_t - 0.1 * b.h)
    tank_w = b.w * rng.uniform(0.85, 1.0)
    b.box("tank", (b.x0, b.x0 + tank_d), (tank_bottom, b.h - lid_t), (-tank_w / 2, tank_w / 2))
    b.box("tank_lid", (b.x0, b.x0 + tank_d + 0.01 * b.d), (b.h - lid_t, b.h), (b.z0, b.z1))
    b.support("tank", b.h, (b.x0, b.x0 + tank_d), (b.z0, b.z1))
    flush = min(0.03, 0.1 * b.w)
    b.box(
        "flush",
        (b.x0 + tank_d, b.x0 + tank_d + 0.02 * b.d),
        (b.h - lid_t - 2 * flush, b.h - lid_t - flush),
        (tank_w / 2 - 3 * flush, tank_w / 2 - flush),
    )

    bowl_x0 = b.x0 + 0.7 * tank_d
    centre = ((bowl_x0 + b.x1) / 2, 0.0)
    radii = ((b.x1 - bowl_x0) / 2, b.w * rng.uniform(0.75, 0.95) / 2)
    rim = seat_y - seat_t
    bowl_bottom = rim * rng.uniform(0.35, 0.5)
    b.add(
        "bowl",
        primitives.revolved(
            _bowl_profile((bowl_bottom, rim), 0.7, 0.18, 0.5, 0.6 * (rim - bowl_bottom)),
            centre,
            radii,
        ),
    )
    foot = (radii[0] * 0.5, radii[1] * 0.55)
    b.add(
        "bowl",
        primitives.frustum((centre[0] - 0.2 * radii[0], 0.0), foot, (0.0, bowl_bottom + 0.01), 1.2),
    )
    # The trap's bulk joining the bowl to the tank.
    b.box(
        "bowl",
        (b.x0 + 0.5 * tank_d, centre[0]),
        (0.0, rim - 0.1 * (rim - bowl_bottom)),
        (-0.45 * radii[1], 0.45 * radii[1]),
    )

    ring = [(0.62, rim), (1.0, rim), (1.0, seat_y), (0.62, seat_y), (0.62, rim)]
    b.add("seat", primitives.revolved(ring, centre, radii))
    cover_t = min(0.02, 0.03 * b.h)
    if rng.random() < 0.6:
        b.add("lid", primitives.disc(centre, radii, (seat_y, seat_y + cover_t)))
    else:
        # Lid up, leaning on the tank.
        ry = min(radii[0], (b.h - lid_t - seat_y) / 2)
        x = (b.x0 + tank_d, b.x0 + tank_d + cover_t)
        lid = primitives.turned_to_x(primitives.disc((0.0, 0.0), (ry, radii[1]), x))
        lid.apply_translation([0.0, seat_y + ry, 0.0])
        b.add("lid", lid)


def sink(b: ShapeBuilder, rng: np.random.Generator) -> None:
    """A basin (oval or rectangular) with a faucet on a deck behind it: on its own when the
    box is low, otherwise on a pedestal or as a vessel on a vanity unit."""
    style = "basin" if b.h < 0.45 else pick(rng, ("pedestal", "vanity"))
    faucet_h = (
        vary(rng, 0.12, 0.3, 0.45 * b.h) if style != "basin" else b.h * rng.uniform(0.25, 0.45)
    )
    rim = b.h - faucet_h
    deck = vary(rng, 0.06, 0.12, 0.25 * b.d)
    x = (b.x0 + deck, b.x1)
    if style == "vanity":
        vessel_h = vary(rng, 0.1, 0.16, 0.3 * rim)
        slab = rim - vessel_h
        top_t = vary(rng, 0.02, 0.04, 0.1 * slab)
        b.box("top", (b.x0, b.x1), (slab - top_t, slab), (b.z0, b.z1))
        bottom = case_base(
            b, (b.x0, b.x1 - 0.02 * b.d), (b.z0, b.z1), pick(rng, ("plinth", "legs")), rng
        )
        layout = [CaseRow("door", 2 if b.w > 0.7 else 1)] + (
            [CaseRow("drawer", weight=0.3)] if rng.random() < 0.5 else []
        )
        case(
            b,
            (b.x0, b.x1 - 0.02 * b.d),
            (bottom, slab - top_t),
            (b.z0 + 0.01 * b.w, b.z1 - 0.01 * b.w),
            layout,
            rng,
        )
        width = b.w * rng.uniform(0.45, 0.7)
        _basin(b, rng, x, (slab, rim), (-width / 2, width / 2), oval=True)
        base = slab
    else:
        low = 0.0 if style == "basin" else rim - vary(rng, 0.15, 0.22, 0.4 * rim)
        oval = rng.random() < 0.5
        _basin(b, rng, x, (low, rim), (b.z0, b.z1), oval)
        b.box(
            "deck",
            (b.x0, b.x0 + deck + 0.05 * b.d),
            (rim - min(0.04, 0.3 * (rim - low)), rim),
            (-0.3 * b.w, 0.3 * b.w),
        )
        if style == "pedestal":
            radii = (0.15 * b.d, 0.2 * b.w)
            b.add(
                "pedestal",
                primitives.frustum(
                    ((x[0] + x[1]) / 2 - 0.05 * b.d, 0.0), radii, (0.0, low + 0.01), 1.4
                ),
            )
        base = rim
    _faucet(b, rng, b.x0 + deck / 2, base, b.h - base)


def _basin(
    b: ShapeBuilder,
    rng: np.random.Generator,
    x: tuple[float, float],
    y: tuple[float, float],
    z: tuple[float, float],
    oval: bool,
) -> None:
    """A hollow basin filling x by z: an oval bowl or a rectangular one with sloped sides."""
    centre = ((x[0] + x[1]) / 2, (z[0] + z[1]) / 2)
    radii = ((x[1] - x[0]) / 2, (z[1] - z[0]) / 2)
    outer = rng.uniform(0.5, 0.8) if oval else rng.uniform(0.7, 0.95)
    profile = _bowl_profile(y, outer, 0.12, outer - 0.2, 0.7 * (y[1] - y[0]))
    b.add("basin", primitives.revolved(profile, centre, radii, square=not oval))


def _faucet(b: ShapeBuilder, rng: np.random.Generator, x: float, y: float, height: float) -> None:
    """A column rising from y to y + height with a spout reaching forward over the basin."""
    radius = min(0.014, 0.08 * height)
    top = y + height - radius
    reach = vary(rng, 0.08, 0.16, 0.4 * b.d)
    b.add("faucet", primitives.rod((x, y, 0.0), (x, top + radius, 0.0), radius))
    b.add("faucet", primitives.rod((x, top, 0.0), (x + reach, top, 0.0), 0.8 * radius))
    if rng.random() < 0.5:
        # Separate hot and cold taps.
        for z in (-0.15 * b.w, 0.15 * b.w):
            b.add("faucet", primitives.rod((x, y, z), (x, y + 0.4 * height, z), radius))


def bathtub(b: ShapeBuilder, rng: np.random.Generator) -> None:
    """A built-in rectangular tub with an apron, or a freestanding oval one on feet or a
    plinth; a spout at the tap end (-z)."""
    if rng.random() < 0.55:
        # Built in: upright apron all round, sloped sides inside; taps at the -z end.
        floor = b.h * rng.uniform(0.15, 0.3)
        wall = rng.uniform(0.08, 0.14)
        profile = _bowl_profile(
            (0.0, b.h), 1.0, wall, 1.0 - wall - rng.uniform(0.05, 0.15), b.h - floor
        )
        b.add("shell", primitives.revolved(profile, (0.0, 0.0), (b.d / 2, b.w / 2), square=True))
        spout_z = b.z0 + wall * b.w / 2
    else:
        feet = rng.random() < 0.6
        lift = vary(rng, 0.05, 0.12, 0.2 * b.h) if feet else 0.0
        bottom_ratio = rng.uniform(0.7, 0.85)
        profile = _bowl_profile(
            (lift, b.h), bottom_ratio, 0.08, bottom_ratio - 0.1, 0.8 * (b.h - lift)
        )
        b.add("shell", primitives.revolved(profile, (0.0, 0.0), (b.d / 2, b.w / 2)))
        if feet:
            for sx in (-1, 1):
                for sz in (-1, 1):
                    centre = (sx * 0.3 * bottom_ratio * b.d, sz * 0.35 * bottom_ratio * b.w)
                    b.add(
                        "foot",
                        primitives.frustum(
                            centre,
                            (0.03 * b.d, 0.02 * b.w),
                            (0.0, lift + 0.01),
                            1.6,
                            primitives.SMALL_SECTIONS,
                        ),
                    )
        else:
            b.add(
                "shell",
                primitives.disc(
                    (0.0, 0.0),
                    (0.4 * bottom_ratio * b.d, 0.4 * bottom_ratio * b.w),
                    (0.0, 0.02 * b.h),
                ),
            )
        spout_z = b.z0 + 0.1 * b.w
    radius = min(0.015, 0.05 * b.h)
    y = b.h - 4 * radius
    b.add(
        "faucet",
        primitives.rod(
            (0.0, y, spout_z - 0.01 * b.w), (0.0, y, spout_z + min(0.15, 0.1 * b.w)), radius
        ),
    )
