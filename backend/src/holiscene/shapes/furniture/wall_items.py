"""Flat things on or in walls, facing +x with their back at -x: picture, mirror, window,
door, curtain, television (which may also stand on furniture)."""

from __future__ import annotations

import itertools
import math

import numpy as np

from .. import primitives
from ..builder import ShapeBuilder, pick, vary
from .common import frame


def picture(b: ShapeBuilder, rng: np.random.Generator) -> None:
    """A frame around a canvas set back from its face, sometimes a mat; or a frameless
    canvas print on a stretcher set in from its edges."""
    if rng.random() < 0.2:
        skin = rng.uniform(0.15, 0.35) * b.d
        inset = vary(rng, 0.01, 0.03, 0.1 * min(b.h, b.w))
        b.box("canvas", (b.x1 - skin, b.x1), (0.0, b.h), (b.z0, b.z1))
        b.box("stretcher", (b.x0, b.x1 - skin), (inset, b.h - inset), (b.z0 + inset, b.z1 - inset))
        return
    width = vary(rng, 0.015, 0.07, 0.2 * min(b.h, b.w))
    opening_y, opening_z = frame(b, "frame", (b.x0, b.x1), (0.0, b.h), (b.z0, b.z1), width)
    if rng.random() < 0.4:
        mat = rng.uniform(0.06, 0.15) * min(b.h, b.w)
        b.box("mat", (b.x0, b.x1 - 0.4 * b.d), opening_y, opening_z)
        opening_y = (opening_y[0] + mat, opening_y[1] - mat)
        opening_z = (opening_z[0] + mat, opening_z[1] - mat)
        b.box("canvas", (b.x0, b.x1 - 0.35 * b.d), opening_y, opening_z)
    else:
        b.box("canvas", (b.x0, b.x1 - 0.3 * b.d), opening_y, opening_z)


def mirror(b: ShapeBuilder, rng: np.random.Generator) -> None:
    """Rectangular (framed or frameless on a backing board) or oval in a ring frame."""
    glass_x = (b.x0, b.x1 - 0.25 * b.d)
    if rng.random() < 0.3:
        inner = rng.uniform(0.8, 0.93)
        ring = [(inner, b.x0), (1.0, b.x0), (1.0, b.x1), (inner, b.x1), (inner, b.x0)]
        radii = (b.h / 2, b.w / 2)
        glass = [
            (0.0, glass_x[0]),
            (inner + 0.01, glass_x[0]),
            (inner + 0.01, glass_x[1]),
            (0.0, glass_x[1]),
        ]
        for name, profile in (("frame", ring), ("glass", glass)):
            mesh = primitives.turned_to_x(primitives.revolved(profile, (0.0, 0.0), radii))
            mesh.apply_translation([0.0, b.h / 2, 0.0])
            b.add(name, mesh)
        return
    if rng.random() < 0.7:
        width = vary(rng, 0.02, 0.08, 0.15 * min(b.h, b.w))
        opening_y, opening_z = frame(b, "frame", (b.x0, b.x1), (0.0, b.h), (b.z0, b.z1), width)
        b.box("glass", glass_x, opening_y, opening_z)
    else:
        # Frameless: bevelled glass on a slightly smaller backing board.
        back = rng.uniform(0.3, 0.6) * b.d
        inset = vary(rng, 0.005, 0.02, 0.1 * min(b.h, b.w))
        b.box("backing", (b.x0, b.x0 + back), (inset, b.h - inset), (b.z0 + inset, b.z1 - inset))
        b.box("glass", (b.x0 + back, b.x1), (0.0, b.h), (b.z0, b.z1))


def window(b: ShapeBuilder, rng: np.random.Generator) -> None:
    """A frame with glazing bars in a grid of panes; a sill sticking out below on most."""
    sill_h = vary(rng, 0.02, 0.05, 0.1 * b.h) if rng.random() < 0.6 else 0.0
    frame_d = b.d * rng.uniform(0.4, 0.7) if sill_h else b.d
    if sill_h:
        b.box("sill", (b.x0, b.x1), (0.0, sill_h), (b.z0, b.z1))
    width = vary(rng, 0.04, 0.08, 0.15 * min(b.h, b.w))
    x = (b.x0, b.x0 + frame_d)
    opening_y, opening_z = frame(b, "frame", x, (sill_h, b.h), (b.z0, b.z1), width)
    b.box("glass", (x[0] + 0.45 * frame_d, x[0] + 0.55 * frame_d), opening_y, opening_z)
    columns = int(np.clip(round((opening_z[1] - opening_z[0]) / rng.uniform(0.4, 0.9)), 1, 4))
    rows = int(rng.integers(1, 3)) if opening_y[1] - opening_y[0] > 0.6 else 1
    bar = vary(rng, 0.02, 0.045, 0.1 * min(b.h, b.w))
    bar_x = (x[0] + 0.2 * frame_d, x[0] + 0.8 * frame_d)
    for z in np.linspace(*opening_z, columns + 1)[1:-1]:
        b.box("mullion", bar_x, opening_y, (z - bar / 2, z + bar / 2))
    for y in np.linspace(*opening_y, rows + 1)[1:-1]:
        b.box("mullion", bar_x, (y - bar / 2, y + bar / 2), opening_z)


def door(b: ShapeBuilder, rng: np.random.Generator) -> None:
    """A leaf in a frame (jambs and head), flat or with raised panels on both faces, and a
    lever handle on each side near the latch edge."""
    jamb = vary(rng, 0.04, 0.1, 0.1 * b.w, 0.1 * b.h)
    leaf_y, leaf_z = frame(b, "frame", (b.x0, b.x1), (0.0, b.h), (b.z0, b.z1), jamb, bottom=False)
    gap = 0.004
    leaf_t = min(0.045, 0.5 * b.d)
    leaf_x = (-leaf_t / 2, leaf_t / 2)
    leaf_y = (leaf_y[0] + min(0.01, 0.02 * b.h), leaf_y[1] - gap)
    leaf_z = (leaf_z[0] + gap, leaf_z[1] - gap)
    b.box("leaf", leaf_x, leaf_y, leaf_z)

    relief = min(0.008, (b.d / 2 - leaf_t / 2) / 4)
    rows, columns = pick(rng, ((0, 0), (2, 1), (2, 2), (3, 2), (1, 1)))
    if rows:
        margin = 0.15 * min(leaf_z[1] - leaf_z[0], leaf_y[1] - leaf_y[0])
        ys = np.linspace(leaf_y[0] + margin, leaf_y[1] - margin, rows + 1)
        zs = np.linspace(leaf_z[0] + margin, leaf_z[1] - margin, columns + 1)
        for y_lo, y_hi in itertools.pairwise(ys):
            for z_lo, z_hi in itertools.pairwise(zs):
                y, z = (
                    (y_lo + 0.3 * margin, y_hi - 0.3 * margin),
                    (z_lo + 0.3 * margin, z_hi - 0.3 * margin),
                )
                b.box("panel", (leaf_x[1], leaf_x[1] + relief), y, z)
                b.box("panel", (leaf_x[0] - relief, leaf_x[0]), y, z)

    reach = min(0.06, 0.9 * (b.d / 2 - leaf_t / 2))
    if reach > 0.002:
        _levers(b, rng, leaf_t / 2 + reach, reach, leaf_z)


def _levers(
    b: ShapeBuilder, rng: np.random.Generator, tip: float, reach: float, leaf_z: tuple[float, float]
) -> None:
    """A spindle through the leaf with a lever on each face, pointing away from the latch."""
    width = leaf_z[1] - leaf_z[0]
    latch = 1 if rng.random() < 0.5 else -1
    z = leaf_z[1] - 0.07 * width if latch > 0 else leaf_z[0] + 0.07 * width
    y = min(1.0, 0.48 * b.h)
    radius = min(0.02, 0.03 * b.h)
    lever = (z - 0.15 * width, z) if latch > 0 else (z, z + 0.15 * width)
    b.add("handle", primitives.rod((-tip, y, z), (tip, y, z), radius))
    for x in ((tip - 0.3 * reach, tip), (-tip, -tip + 0.3 * reach)):
        b.box("handle", x, (y - radius / 2, y + radius / 2), lever)


def curtain(b: ShapeBuilder, rng: np.random.Generator) -> None:
    """One or two wavy panels (folds along the width) hanging from an optional rod; two
    panels may be drawn apart."""
    rod = vary(rng, 0.01, 0.02, b.d / 2, 0.03 * b.h) if rng.random() < 0.7 else 0.0
    if rod:
        b.add("rod", primitives.rod((0.0, b.h - rod, b.z0), (0.0, b.h - rod, b.z1), rod))
    thickness = min(0.01, 0.2 * b.d)
    amplitude = (b.d - thickness) / 2
    # Folds a few times wider than deep, whatever the box depth: soft waves, not pleats.
    wavelength = float(np.clip(amplitude * rng.uniform(3.0, 5.0), 0.08, 0.4))
    top = b.h - rod
    if rng.random() < 0.3:
        spans = [(b.z0, b.z1)]
    else:
        half = b.w * (1 - rng.uniform(0.0, 0.5)) / 2
        spans = [(b.z0, b.z0 + half), (b.z1 - half, b.z1)]
    for z0, z1 in spans:
        # Six samples a wave: smooth enough, and the fit stretches the crests onto the box.
        waves = (z1 - z0) / wavelength
        count = int(np.clip(math.ceil(waves * 6), 8, 160))
        z = np.linspace(z0, z1, count + 1)
        phase = rng.uniform(0, 2 * np.pi)
        x = amplitude * np.sin(2 * np.pi * (z - z0) / wavelength + phase)
        b.add("curtain", primitives.band(np.column_stack([x, z]), thickness, (0.0, top)))


def television(b: ShapeBuilder, rng: np.random.Generator) -> None:
    """A deep box is a CRT (a tube tapering behind the front); otherwise a flat panel with
    a bezel, on a foot and neck or wall mounted."""
    if b.d > 0.35 * b.w:
        _crt(b, rng)
        return
    panel_t = vary(rng, 0.03, 0.07, 0.6 * b.d)
    if rng.random() < 0.6:
        # On a stand: the foot fills the depth, the panel sits centred above it.
        foot_t = vary(rng, 0.01, 0.025, 0.05 * b.h)
        bottom = rng.uniform(0.05, 0.15) * b.h
        foot_w = b.w * rng.uniform(0.25, 0.6)
        b.box("stand", (b.x0, b.x1), (0.0, foot_t), (-foot_w / 2, foot_w / 2))
        neck = min(0.03, 0.2 * b.d)
        b.box(
            "stand",
            (-panel_t / 2 - neck, -panel_t / 2),
            (foot_t, bottom + 0.3 * (b.h - bottom)),
            (-0.04 * b.w, 0.04 * b.w),
        )
        x = (-panel_t / 2, panel_t / 2)
    else:
        bottom = 0.0
        x = (b.x1 - panel_t, b.x1)
        b.box("mount", (b.x0, x[0]), (0.3 * b.h, 0.7 * b.h), (-0.2 * b.w, 0.2 * b.w))
    _screen(b, rng, x, (bottom, b.h), (b.z0, b.z1))


def _screen(
    b: ShapeBuilder,
    rng: np.random.Generator,
    x: tuple[float, float],
    y: tuple[float, float],
    z: tuple[float, float],
) -> None:
    """A body with a bezel round a screen set just behind the bezel's face."""
    face = min(0.01, 0.3 * (x[1] - x[0]))
    b.box("body", (x[0], x[1] - face), y, z)
    bezel = vary(rng, 0.008, 0.04, 0.1 * (y[1] - y[0]), 0.1 * (z[1] - z[0]))
    screen_y, screen_z = frame(b, "bezel", (x[1] - face, x[1]), y, z, bezel)
    b.box("screen", (x[1] - face, x[1] - face / 3), screen_y, screen_z)


def _crt(b: ShapeBuilder, rng: np.random.Generator) -> None:
    front = b.d * rng.uniform(0.3, 0.45)
    shrink = rng.uniform(0.15, 0.3)
    back = [(b.h * shrink, b.h * (1 - shrink / 2)), (b.z0 + b.w * shrink, b.z1 - b.w * shrink)]
    b.add("body", primitives.tapered_box(0, (b.x0, b.x1 - front), back, [(0.0, b.h), (b.z0, b.z1)]))
    _screen(b, rng, (b.x1 - front, b.x1), (0.0, b.h), (b.z0, b.z1))
