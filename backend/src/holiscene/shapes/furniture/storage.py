"""Storage: dresser, night stand, cabinet, bookshelf, shelves, refrigerator.

All but wall shelves and racks are `case`s; what differs is the row layout, the base and
whether a top slab overhangs the carcass.
"""

from __future__ import annotations

import numpy as np

from ..builder import ShapeBuilder, pick, vary
from .case import CaseRow, CellKind, case
from .common import BaseStyle, HandleStyle, case_base, four_legs

_HANDLES: tuple[HandleStyle, ...] = ("bar", "knob", "none")


def _cabinet_body(
    b: ShapeBuilder,
    rng: np.random.Generator,
    rows: list[CaseRow],
    base: BaseStyle,
    handle_style: HandleStyle,
    top_slab: bool,
    back_panel: bool = True,
) -> None:
    """A case on a base, under an optional overhanging top slab; its top is a surface
    (the slab, or the carcass behind the fronts)."""
    overhang = vary(rng, 0.0, 0.025, 0.05 * b.d, 0.05 * b.w) if top_slab else 0.0
    x = (b.x0, b.x1 - overhang)
    z = (b.z0 + overhang, b.z1 - overhang)
    bottom = case_base(b, x, z, base, rng)
    top = b.h
    if top_slab:
        thickness = vary(rng, 0.018, 0.04, 0.1 * b.h)
        top = b.h - thickness
        b.box("top", (b.x0, b.x1), (top, b.h), (b.z0, b.z1))
    front = case(
        b,
        x,
        (bottom, top),
        z,
        rows,
        rng,
        handle_style=handle_style,
        back_panel=back_panel,
        top_panel=not top_slab,
    )
    b.support("top", b.h, (b.x0, b.x1 if top_slab else front), (b.z0, b.z1))


def _rows_fitting(height: float, wanted: int, min_row: float) -> int:
    """At most `wanted` rows, but no row lower than `min_row` (and at least one)."""
    return int(max(1, min(wanted, height // min_row)))


def dresser(b: ShapeBuilder, rng: np.random.Generator) -> None:
    """Rows of drawers; wide ones in two columns, often a row of small drawers on top."""
    rows = _rows_fitting(b.h, int(rng.integers(3, 6)), 0.12)
    columns = 2 if b.w > 0.9 and rng.random() < 0.5 else 1
    layout = [CaseRow("drawer", columns) for _ in range(rows)]
    if rows >= 3 and rng.random() < 0.6:
        layout[-1] = CaseRow("drawer", columns + int(rng.integers(1, 3)), weight=0.7)
    base: BaseStyle = pick(rng, ("plinth", "legs", "none"))
    handles = pick(rng, _HANDLES, p=(0.5, 0.35, 0.15))
    _cabinet_body(b, rng, layout, base, handles, top_slab=rng.random() < 0.8)


def night_stand(b: ShapeBuilder, rng: np.random.Generator) -> None:
    """One to three drawers, sometimes an open niche or a door below; often on legs."""
    drawers = _rows_fitting(b.h, int(rng.integers(1, 4)), 0.1)
    layout = [CaseRow("drawer") for _ in range(drawers)]
    below: CellKind | None = pick(rng, (None, "open", "door"), p=(0.5, 0.3, 0.2))
    if below is not None and drawers < 3:
        layout.insert(0, CaseRow(below, weight=1.5))
    base: BaseStyle = pick(rng, ("legs", "plinth", "none"), p=(0.5, 0.25, 0.25))
    handles = pick(rng, _HANDLES, p=(0.4, 0.45, 0.15))
    _cabinet_body(b, rng, layout, base, handles, top_slab=rng.random() < 0.7)


def cabinet(b: ShapeBuilder, rng: np.random.Generator) -> None:
    """Doors (in pairs when wide), maybe a drawer row on top or an open hutch; or a filing
    cabinet's stack of drawers."""
    columns = 1 if b.w < 0.5 else (3 if b.w > 1.5 else int(rng.integers(1, 3)))
    style = pick(rng, ("doors", "doors_drawer", "hutch", "filing"), p=(0.4, 0.25, 0.15, 0.2))
    if style == "filing":
        layout = [
            CaseRow("drawer") for _ in range(_rows_fitting(b.h, int(rng.integers(2, 5)), 0.2))
        ]
    else:
        tall = b.h > 1.3
        layout = [CaseRow("door", columns)] + ([CaseRow("door", columns)] if tall else [])
        if style == "doors_drawer":
            layout.append(CaseRow("drawer", columns, weight=0.35))
        elif style == "hutch":
            layout.append(CaseRow("open", 1, weight=0.8))
    base: BaseStyle = pick(rng, ("plinth", "legs", "none"))
    handles = pick(rng, _HANDLES, p=(0.55, 0.3, 0.15))
    _cabinet_body(b, rng, layout, base, handles, top_slab=rng.random() < 0.5)


def bookshelf(b: ShapeBuilder, rng: np.random.Generator) -> None:
    """Open shelves (one or two bays), usually a back panel, sometimes doors at the bottom."""
    levels = int(np.clip(round(b.h / rng.uniform(0.28, 0.42)), 2, 8))
    columns = 2 if b.w > 1.0 and rng.random() < 0.5 else 1
    layout = [CaseRow("open", columns) for _ in range(levels)]
    if levels >= 4 and rng.random() < 0.25:
        layout[0] = CaseRow("door", columns, weight=1.3)
    base: BaseStyle = pick(rng, ("plinth", "none"))
    handles: HandleStyle = pick(rng, ("bar", "knob"))
    _cabinet_body(b, rng, layout, base, handles, top_slab=False, back_panel=rng.random() < 0.9)


def shelves(b: ShapeBuilder, rng: np.random.Generator) -> None:
    """A metal rack, boards on wall brackets, or an open cube unit without a back."""
    style = pick(rng, ("rack", "wall", "cubes"))
    if style == "cubes":
        rows = int(np.clip(round(b.h / rng.uniform(0.3, 0.4)), 1, 5))
        columns = int(np.clip(round(b.w / rng.uniform(0.3, 0.4)), 1, 5))
        layout = [CaseRow("open", columns) for _ in range(rows)]
        _cabinet_body(b, rng, layout, "none", "none", top_slab=False, back_panel=False)
        return
    levels = int(np.clip(round(b.h / rng.uniform(0.3, 0.45)), 2, 7))
    board = vary(rng, 0.015, 0.035, 0.3 * b.h / levels)
    if style == "rack":
        post = vary(rng, 0.02, 0.04, 0.2 * b.d, 0.2 * b.w)
        four_legs(b, (b.x0, b.x1), (b.z0, b.z1), (0.0, b.h), post, "square")
        lowest = board + vary(rng, 0.05, 0.15, 0.3 * b.h / levels)
        # The posts stand in the boards' corners: keep the usable area clear of them.
        usable_x, usable_z = (b.x0 + post, b.x1 - post), (b.z0 + post, b.z1 - post)
        arm = 0.0
    else:
        # Each board hangs on brackets reaching `drop` below it; the lowest ones reach y = 0.
        drop = 0.6 * (b.h - board) / (levels - 0.4)
        lowest = board + drop
        plate, arm = min(0.006, 0.05 * b.d), min(0.012, 0.3 * drop)
        usable_x, usable_z = (b.x0 + plate, b.x1), (b.z0, b.z1)
    tops = [float(t) for t in np.linspace(lowest, b.h, levels)]
    for k, top in enumerate(tops):
        b.box("shelf", (b.x0, b.x1), (top - board, top), (b.z0, b.z1))
        if style == "wall":
            _brackets(b, top - board, drop, plate, arm)
        # Free height up to the next board, or to the bracket arms under it.
        clearance = tops[k + 1] - board - arm - top if k + 1 < levels else np.inf
        b.support("shelf", top, usable_x, usable_z, clearance=clearance)


def _brackets(b: ShapeBuilder, under: float, drop: float, plate: float, arm: float) -> None:
    """Two L brackets under a wall shelf: a plate on the wall, an arm under the board."""
    width = min(0.03, 0.1 * b.w)
    for centre in (b.z0 + 0.2 * b.w, b.z1 - 0.2 * b.w):
        z = (centre - width / 2, centre + width / 2)
        b.box("bracket", (b.x0, b.x0 + plate), (under - drop, under), z)
        b.box("bracket", (b.x0 + plate, b.x0 + 0.8 * b.d), (under - arm, under), z)


def refrigerator(b: ShapeBuilder, rng: np.random.Generator) -> None:
    """Top freezer, bottom freezer (drawer), side by side, or one door; long bar handles."""
    styles = ("top_freezer", "bottom_freezer", "side_by_side", "single")
    # A box under a metre is a mini fridge: one door.
    style = pick(rng, styles, p=(0.35, 0.3, 0.2, 0.15)) if b.h >= 1.0 else "single"
    freezer = rng.uniform(0.25, 0.4)
    layout = {
        "top_freezer": [CaseRow("door", weight=1 - freezer), CaseRow("door", weight=freezer)],
        "bottom_freezer": [
            CaseRow("drawer", weight=freezer),
            CaseRow("door", int(rng.integers(1, 3)), weight=1 - freezer),
        ],
        "side_by_side": [CaseRow("door", 2)],
        "single": [CaseRow("door")],
    }[style]
    x = (b.x0, b.x1)
    bottom = case_base(b, x, (b.z0, b.z1), "plinth", rng) if rng.random() < 0.7 else 0.0
    front = case(b, x, (bottom, b.h), (b.z0, b.z1), layout, rng, handle_style="bar")
    b.support("top", b.h, (b.x0, front), (b.z0, b.z1))
