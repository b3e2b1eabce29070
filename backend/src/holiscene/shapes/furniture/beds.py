"""Bed: headboard at -x (against the wall), foot at +x, width along z."""

from __future__ import annotations

import numpy as np

from ..builder import ShapeBuilder, pick, vary
from .common import four_legs


def bed(b: ShapeBuilder, rng: np.random.Generator) -> None:
    """A frame on legs or a solid base, a mattress, maybe a duvet over its foot end; a
    panel or post headboard (or none), and a footboard on some."""
    headboard = pick(rng, ("panel", "posts", "none"), p=(0.55, 0.3, 0.15))
    if b.h > 0.75 and headboard == "none":
        headboard = "panel"  # a tall box without a headboard would be a block of mattress
    footboard = rng.random() < 0.35
    base = pick(rng, ("legs", "solid"))
    duvet_t = vary(rng, 0.03, 0.07, 0.08 * b.h) if rng.random() < 0.6 else 0.0

    # The sleeping surface: the top of the box without a headboard, else well below it.
    top = b.h if headboard == "none" else b.h * rng.uniform(0.45, 0.75)
    mattress_top = top - duvet_t
    mattress_t = vary(rng, 0.15, 0.3, 0.45 * mattress_top)
    frame_top = mattress_top - mattress_t
    leg_h = vary(rng, 0.08, 0.25, 0.6 * frame_top) if base == "legs" else 0.0

    head_t = vary(rng, 0.04, 0.1, 0.06 * b.d) if headboard != "none" else 0.0
    foot_t = vary(rng, 0.03, 0.06, 0.04 * b.d) if footboard else 0.0
    x_in = (b.x0 + head_t, b.x1 - foot_t)
    b.box("frame", x_in, (leg_h, frame_top), (b.z0, b.z1))
    if base == "legs":
        thickness = vary(rng, 0.05, 0.09, 0.1 * b.w)
        four_legs(
            b,
            x_in,
            (b.z0, b.z1),
            (0.0, leg_h),
            thickness,
            pick(rng, ("square", "round")),
            0.02 * b.w,
            3 if b.w > 1.5 else 2,
        )

    mattress_x = (x_in[0] + 0.01 * b.d, x_in[1] - min(0.03, 0.05 * b.d))
    mattress_z = (b.z0 + min(0.03, 0.05 * b.w), b.z1 - min(0.03, 0.05 * b.w))
    b.box("mattress", mattress_x, (frame_top, mattress_top), mattress_z)
    pillow_end = mattress_x[1]
    if duvet_t > 0:
        # Covers the foot end and hangs over the sides; the head end stays bare for pillows.
        start = mattress_x[0] + rng.uniform(0.25, 0.4) * (mattress_x[1] - mattress_x[0])
        drop = vary(rng, 0.1, 0.25, 0.8 * mattress_t)
        b.box("duvet", (start, x_in[1]), (mattress_top - drop, top), (b.z0, b.z1))
        b.support("duvet", top, (start, x_in[1]), (b.z0, b.z1))
        pillow_end = start
    b.support("mattress", mattress_top, (mattress_x[0], pillow_end), mattress_z)

    if headboard != "none":
        _end_board(b, rng, "headboard", (b.x0, x_in[0]), b.h, headboard)
    if footboard:
        high = min(top + rng.uniform(0.05, 0.25), b.h)
        _end_board(b, rng, "footboard", (x_in[1], b.x1), high, pick(rng, ("panel", "posts")))


def _end_board(
    b: ShapeBuilder,
    rng: np.random.Generator,
    name: str,
    x: tuple[float, float],
    height: float,
    style: str,
) -> None:
    """A head- or footboard from the floor to `height`: one panel, or a panel between posts."""
    if style == "panel":
        b.box(name, x, (0.0, height), (b.z0, b.z1))
        return
    post = vary(rng, 0.05, 0.09, 0.1 * b.w)
    for z in ((b.z0, b.z0 + post), (b.z1 - post, b.z1)):
        b.box(name, x, (0.0, height), z)
    low = height * rng.uniform(0.35, 0.6)
    inset = 0.2 * (x[1] - x[0])
    b.box(name, (x[0] + inset, x[1] - inset), (low, 0.95 * height), (b.z0 + post, b.z1 - post))
