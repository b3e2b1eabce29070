"""Small things: lamp, pillow, box, books, and the plain box for every other class."""

from __future__ import annotations

import numpy as np

from .. import primitives
from ..builder import ShapeBuilder, pick, vary


def lamp(b: ShapeBuilder, rng: np.random.Generator) -> None:
    """A base (disc, block or vase body), a stem and a shade (drum or cone) whose rim fills
    the footprint. A tall box makes a floor lamp: thin base, long stem, smaller shade."""
    floor_lamp = b.h > 1.0
    shade_h = b.h * (rng.uniform(0.13, 0.22) if floor_lamp else rng.uniform(0.3, 0.45))
    shade_y = (b.h - shade_h, b.h)
    top_ratio = rng.uniform(0.55, 1.0)
    if rng.random() < 0.25:
        # A square shade.
        rim = [(b.x0, b.x1), (b.z0, b.z1)]
        top = [(top_ratio * b.x0, top_ratio * b.x1), (top_ratio * b.z0, top_ratio * b.z1)]
        b.add("shade", primitives.tapered_box(1, shade_y, rim, top))
    else:
        b.add("shade", primitives.frustum((0.0, 0.0), (b.d / 2, b.w / 2), shade_y, top_ratio))

    kind = "disc" if floor_lamp else pick(rng, ("disc", "block", "vase"))
    base_r = (rng.uniform(0.3, 0.6) * b.d / 2, rng.uniform(0.3, 0.6) * b.w / 2)
    if kind == "vase":
        body_top = shade_y[0] * rng.uniform(0.5, 0.8)
        belly = rng.uniform(0.7, 1.0)
        profile = [
            (0.0, 0.0),
            (0.6, 0.0),
            (belly, 0.35 * body_top),
            (0.85, 0.7 * body_top),
            (0.3, body_top),
            (0.0, body_top),
        ]
        b.add("base", primitives.revolved(profile, (0.0, 0.0), base_r))
        stem_from = body_top
    else:
        thick = (0.015, 0.04) if kind == "disc" else (0.05, 0.12)
        base_t = vary(rng, *thick, 0.3 * shade_y[0])
        if kind == "disc":
            b.add("base", primitives.disc((0.0, 0.0), base_r, (0.0, base_t)))
        else:
            b.box("base", (-base_r[0], base_r[0]), (0.0, base_t), (-base_r[1], base_r[1]))
        stem_from = base_t
    # The stem runs up inside the shade to where a bulb would sit.
    stem = min(0.012, 0.05 * min(b.d, b.w))
    b.add(
        "stem",
        primitives.disc(
            (0.0, 0.0),
            (stem, stem),
            (stem_from, shade_y[0] + 0.5 * shade_h),
            primitives.SMALL_SECTIONS,
        ),
    )


def pillow(b: ShapeBuilder, rng: np.random.Generator) -> None:
    """A cushion lying flat: boxy in plan, plump in the middle, thin at the seams."""
    b.add(
        "pillow",
        primitives.superellipsoid(
            (b.x0, b.x1), (0.0, b.h), (b.z0, b.z1), rng.uniform(0.2, 0.5), rng.uniform(0.3, 0.7)
        ),
    )


def box(b: ShapeBuilder, rng: np.random.Generator) -> None:
    """A carton with its top flaps, a storage box with a lid, or an open crate."""
    style = pick(rng, ("carton", "lidded", "crate"))
    if style == "crate":
        wall = vary(rng, 0.01, 0.025, 0.1 * min(b.d, b.w))
        floor = min(wall, 0.2 * b.h)
        b.box("box", (b.x0, b.x1), (0.0, floor), (b.z0, b.z1))
        b.box("box", (b.x0, b.x0 + wall), (floor, b.h), (b.z0, b.z1))
        b.box("box", (b.x1 - wall, b.x1), (floor, b.h), (b.z0, b.z1))
        b.box("box", (b.x0 + wall, b.x1 - wall), (floor, b.h), (b.z0, b.z0 + wall))
        b.box("box", (b.x0 + wall, b.x1 - wall), (floor, b.h), (b.z1 - wall, b.z1))
        return
    if style == "lidded":
        lid = b.h * rng.uniform(0.1, 0.25)
        overhang = vary(rng, 0.003, 0.01, 0.05 * min(b.d, b.w))
        b.box(
            "box",
            (b.x0 + overhang, b.x1 - overhang),
            (0.0, b.h - lid),
            (b.z0 + overhang, b.z1 - overhang),
        )
        b.box("lid", (b.x0, b.x1), (b.h - lid, b.h), (b.z0, b.z1))
    else:
        # Two flaps meeting along a seam over the middle.
        flap = vary(rng, 0.003, 0.008, 0.1 * b.h)
        seam = vary(rng, 0.002, 0.01, 0.1 * b.w)
        b.box("box", (b.x0, b.x1), (0.0, b.h - flap), (b.z0, b.z1))
        b.box("flap", (b.x0, b.x1), (b.h - flap, b.h), (b.z0, -seam / 2))
        b.box("flap", (b.x0, b.x1), (b.h - flap, b.h), (seam / 2, b.z1))
    b.support("top", b.h, (b.x0, b.x1), (b.z0, b.z1))


def books(b: ShapeBuilder, rng: np.random.Generator) -> None:
    """Upright books side by side along z (spines facing +x) of varied height, depth and
    thickness; a low, wide box gets a pile of books lying flat instead."""
    if b.h < 0.5 * min(b.d, b.w):
        _pile(b, rng)
        return
    thickness = rng.uniform(0.012, 0.05, size=200)
    count = int(np.clip(np.searchsorted(np.cumsum(thickness), b.w) + 1, 1, 40))
    edges = np.concatenate([[0.0], np.cumsum(thickness[:count])])
    edges = b.z0 + edges / edges[-1] * b.w  # stretch the row to fill the width exactly
    heights = b.h * rng.uniform(0.7, 1.0, size=count)
    depths = b.d * rng.uniform(0.75, 1.0, size=count)
    heights[rng.integers(count)] = b.h
    depths[rng.integers(count)] = b.d
    front_aligned = rng.random() < 0.5
    for k in range(count):
        x = (b.x1 - depths[k], b.x1) if front_aligned else (b.x0, b.x0 + depths[k])
        b.box("book", x, (0.0, float(heights[k])), (float(edges[k]), float(edges[k + 1])))


def _pile(b: ShapeBuilder, rng: np.random.Generator) -> None:
    """Books lying flat, each smaller than the box and shifted a little; one fills it."""
    count = int(np.clip(round(b.h / rng.uniform(0.015, 0.05)), 2, 12))
    tops = np.linspace(0.0, b.h, count + 1)
    scales = rng.uniform(0.7, 1.0, size=(count, 2))
    scales[rng.integers(count)] = 1.0
    shifts = rng.uniform(-0.5, 0.5, size=(count, 2)) * (1 - scales) * (b.d, b.w)
    for k in range(count):
        half_x, half_z = scales[k] * (b.d, b.w) / 2
        x = (float(shifts[k, 0] - half_x), float(shifts[k, 0] + half_x))
        z = (float(shifts[k, 1] - half_z), float(shifts[k, 1] + half_z))
        b.box("book", x, (float(tops[k]), float(tops[k + 1])), z)
    b.support("top", b.h, x, z)  # the top book's cover


def generic(b: ShapeBuilder, rng: np.random.Generator) -> None:
    """Any other class: its box, solid."""
    del rng  # same signature as the parametric builders
    b.box("body", (b.x0, b.x1), (0.0, b.h), (b.z0, b.z1))
    b.support("top", b.h, (b.x0, b.x1), (b.z0, b.z1))
