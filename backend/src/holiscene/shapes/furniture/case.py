"""Case furniture: a carcass divided into rows of drawers, doors or open shelves.

Dressers, night stands, cabinets, counters, bookshelves, fridges, desk pedestals and vanity
units are all this one builder with different row layouts. Fronts are overlay style (they
cover the carcass edges) and sit in front of the carcass, with handles in front of them;
so the case's depth runs: carcass | front | handle, and the handle tips reach the front face
of the box.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Literal

import numpy as np

from ..builder import ShapeBuilder, vary
from ..shape import Interval
from .common import HandleStyle, handle

CellKind = Literal["drawer", "door", "open"]

_GAP = 0.003  # between neighbouring fronts: the dark seams that make drawers read as drawers


@dataclass(frozen=True)
class CaseRow:
    kind: CellKind
    columns: int = 1
    weight: float = 1.0  # relative height


def _split(interval: Interval, weights: list[float]) -> list[float]:
    """Boundaries (len(weights) + 1 of them) dividing `interval` in proportion to weights."""
    cumulative = np.concatenate([[0.0], np.cumsum(weights)]) / np.sum(weights)
    return [float(interval[0] + c * (interval[1] - interval[0])) for c in cumulative]


def case(
    b: ShapeBuilder,
    x: Interval,
    y: Interval,
    z: Interval,
    rows: list[CaseRow],
    rng: np.random.Generator,
    *,
    handle_style: HandleStyle = "bar",
    back_panel: bool = True,
    top_panel: bool = True,
) -> float:
    """Rows are listed bottom to top. Open cells become support surfaces.

    Returns the x of the carcass's front plane (behind the fronts and handles).
    """
    depth, height, width = x[1] - x[0], y[1] - y[0], z[1] - z[0]
    has_fronts = any(row.kind != "open" for row in rows)
    has_open = any(row.kind == "open" for row in rows)
    handle_depth = (
        vary(rng, 0.02, 0.035, 0.08 * depth) if has_fronts and handle_style != "none" else 0.0
    )
    front_t = vary(rng, 0.015, 0.025, 0.06 * depth) if has_fronts else 0.0
    xf = x[1] - handle_depth - front_t  # the carcass's front plane
    p = vary(rng, 0.012, 0.025, 0.05 * width, 0.05 * height, 0.2 * depth)  # board thickness
    ys = _split(y, [row.weight for row in rows])

    if has_open:
        _carcass_boards(b, (x[0], xf), y, z, ys, p, back_panel, top_panel)
    else:
        # Nothing shows inside a fully fronted case: one block is enough.
        b.box("carcass", (x[0], xf), y, z)

    back = x[0] + p if (has_open and back_panel) else x[0]
    for i, row in enumerate(rows):
        zs = _split(z, [1.0] * row.columns)
        for j in range(row.columns):
            if row.kind == "open":
                top_row = i == len(rows) - 1
                lo = ys[i] + (p if i == 0 else p / 2)
                hi = ys[i + 1] - ((p if top_panel else 0.0) if top_row else p / 2)
                z_lo = zs[j] + (p if j == 0 else p / 2)
                z_hi = zs[j + 1] - (p if j == row.columns - 1 else p / 2)
                if j > 0:
                    b.box("divider", (back, xf), (lo, hi), (zs[j] - p / 2, zs[j] + p / 2))
                if hi > lo and z_hi > z_lo:
                    b.support("shelf", lo, (back, xf), (z_lo, z_hi), clearance=hi - lo)
                continue
            cell_y = (ys[i] + _GAP / 2, ys[i + 1] - _GAP / 2)
            cell_z = (zs[j] + _GAP / 2, zs[j + 1] - _GAP / 2)
            b.box(f"{row.kind}_front", (xf, xf + front_t), cell_y, cell_z)
            tip = (xf + front_t, x[1])
            if row.kind == "drawer":
                _drawer_handle(b, tip, cell_y, cell_z, handle_style)
            else:
                side = _door_handle_side(j, row.columns, rng)
                _door_handle(b, tip, cell_y, cell_z, side, handle_style)
    return xf


def _carcass_boards(
    b: ShapeBuilder,
    x: Interval,
    y: Interval,
    z: Interval,
    ys: list[float],
    p: float,
    back_panel: bool,
    top_panel: bool,
) -> None:
    inner_z = (z[0] + p, z[1] - p)
    back = x[0] + p if back_panel else x[0]
    b.box("side", x, y, (z[0], z[0] + p))
    b.box("side", x, y, (z[1] - p, z[1]))
    b.box("board", (back, x[1]), (y[0], y[0] + p), inner_z)
    if top_panel:
        b.box("board", (back, x[1]), (y[1] - p, y[1]), inner_z)
    if back_panel:
        b.box("back", (x[0], back), y, inner_z)
    for boundary in ys[1:-1]:
        b.box("board", (back, x[1]), (boundary - p / 2, boundary + p / 2), inner_z)


def _drawer_handle(
    b: ShapeBuilder, tip: Interval, cell_y: Interval, cell_z: Interval, style: HandleStyle
) -> None:
    y = (cell_y[0] + cell_y[1]) / 2
    width = cell_z[1] - cell_z[0]
    smaller = min(width, cell_y[1] - cell_y[0])
    if style == "knob" and width > 0.7:
        # Wide drawers get a knob at each end.
        for z in (cell_z[0] + width / 4, cell_z[1] - width / 4):
            handle(b, tip, y, z, 0.0, False, style, smaller)
        return
    length = min(0.6 * width, max(0.1, 0.3 * width), 0.3)
    handle(b, tip, y, (cell_z[0] + cell_z[1]) / 2, length, False, style, smaller)


def _door_handle_side(column: int, columns: int, rng: np.random.Generator) -> int:
    """-1: handle at the door's low-z edge, +1: at its high-z edge (doors open in pairs)."""
    if columns == 1:
        return -1 if rng.random() < 0.5 else 1
    if columns % 2 == 1 and column == columns - 1:
        return -1
    return 1 if column % 2 == 0 else -1


def _door_handle(
    b: ShapeBuilder,
    tip: Interval,
    cell_y: Interval,
    cell_z: Interval,
    side: int,
    style: HandleStyle,
) -> None:
    height = cell_y[1] - cell_y[0]
    width = cell_z[1] - cell_z[0]
    # Low doors get the pull near their top; tall ones around hand height.
    y = min(cell_y[0] + 0.75 * height, max(cell_y[0] + 0.5 * height, 1.05))
    length = min(0.5 * height, max(0.12, 0.3 * height))
    y = min(max(y, cell_y[0] + length / 2), cell_y[1] - length / 2)
    inset = min(0.05, 0.15 * width)
    z = cell_z[1] - inset if side > 0 else cell_z[0] + inset
    handle(b, tip, y, z, length, True, style, min(width, height))
