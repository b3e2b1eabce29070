"""Closed mesh primitives, placed by world intervals and points rather than by transforms.

Every function returns a closed, outward-facing triangle mesh (a volume) so that shapes made
by concatenating them are closed part by part. Round things take few sections: a generated
scene is ray cast, and a chair of 16-sided legs would cost more than the room.
"""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np
import trimesh
from numpy.typing import ArrayLike, NDArray

from .shape import Interval

SECTIONS = 16  # tops, shades, bowls
SMALL_SECTIONS = 12  # legs, rods, knobs

# Rotation taking trimesh's revolve/extrude axis (+z) onto +y: (x, y, z) -> (x, z, -y).
_Z_TO_Y = trimesh.transformations.rotation_matrix(-np.pi / 2, [1.0, 0.0, 0.0])


def _check(name: str, interval: Interval) -> None:
    if not interval[1] > interval[0]:
        raise ValueError(f"empty {name} interval {interval}")


def box(x: Interval, y: Interval, z: Interval) -> trimesh.Trimesh:
    """The axis-aligned box [x0, x1] x [y0, y1] x [z0, z1]."""
    for name, interval in (("x", x), ("y", y), ("z", z)):
        _check(name, interval)
    mesh: trimesh.Trimesh = trimesh.creation.box(
        bounds=np.array([[x[0], y[0], z[0]], [x[1], y[1], z[1]]])
    )
    return mesh


def rod(
    start: ArrayLike, end: ArrayLike, radius: float, sections: int = SMALL_SECTIONS
) -> trimesh.Trimesh:
    """A round bar from `start` to `end` (any direction)."""
    segment = np.array([start, end], dtype=float)
    if np.linalg.norm(segment[1] - segment[0]) <= 0 or radius <= 0:
        raise ValueError("a rod needs a positive length and radius")
    mesh: trimesh.Trimesh = trimesh.creation.cylinder(
        radius=radius, segment=segment, sections=sections
    )
    return mesh


def revolved(
    profile: Sequence[tuple[float, float]],
    centre: tuple[float, float],
    radii: tuple[float, float],
    sections: int = SECTIONS,
    square: bool = False,
) -> trimesh.Trimesh:
    """A solid of revolution about a vertical axis through (x, z) = `centre`.

    `profile` is a polyline of (relative radius, y in metres); relative radius 1 reaches
    radii = (rx, rz), so the cross-section is an ellipse filling a footprint. A profile that
    starts and ends on the axis (radius 0) closes like a cylinder; one that returns to its
    first point makes a ring. `square` revolves in four steps and turns the result by 45
    degrees, so the cross-section is the rectangle +-radii instead (a rectangular basin).
    """
    points = np.asarray(profile, dtype=float)
    mesh = trimesh.creation.revolve(points, sections=4 if square else sections)
    mesh.apply_transform(_Z_TO_Y)
    spread = 1.0
    if square:
        mesh.apply_transform(trimesh.transformations.rotation_matrix(np.pi / 4, [0.0, 1.0, 0.0]))
        spread = float(np.sqrt(2.0))
    mesh.apply_transform(np.diag([radii[0] * spread, 1.0, radii[1] * spread, 1.0]))
    mesh.apply_translation([centre[0], 0.0, centre[1]])
    return mesh


def disc(
    centre: tuple[float, float],
    radii: tuple[float, float],
    y: Interval,
    sections: int = SECTIONS,
) -> trimesh.Trimesh:
    """A vertical elliptic cylinder: round table tops, lamp bases, posts."""
    _check("y", y)
    return revolved([(0.0, y[0]), (1.0, y[0]), (1.0, y[1]), (0.0, y[1])], centre, radii, sections)


def frustum(
    centre: tuple[float, float],
    radii: tuple[float, float],
    y: Interval,
    top_ratio: float,
    sections: int = SECTIONS,
) -> trimesh.Trimesh:
    """A vertical elliptic cone frustum: `radii` at the bottom, `top_ratio` times them on top."""
    _check("y", y)
    profile = [(0.0, y[0]), (1.0, y[0]), (top_ratio, y[1]), (0.0, y[1])]
    return revolved(profile, centre, radii, sections)


def tapered_box(
    axis: int, along: Interval, start: Sequence[Interval], end: Sequence[Interval]
) -> trimesh.Trimesh:
    """A box along `axis` (0, 1, 2 = x, y, z) whose cross-section shrinks or grows linearly.

    `start` and `end` are the cross-section intervals of the other two axes, in axis order,
    at along[0] and along[1] (a CRT's back, a tapered leg, a square lamp shade).
    """
    _check("along", along)
    for interval in (*start, *end):
        _check("cross-section", interval)
    unit = trimesh.creation.box(bounds=np.array([[0.0, 0.0, 0.0], [1.0, 1.0, 1.0]]))
    others = [a for a in range(3) if a != axis]
    vertices = np.empty_like(unit.vertices)
    for k, corner in enumerate(unit.vertices):
        t = corner[axis]
        vertices[k, axis] = along[0] + t * (along[1] - along[0])
        for slot, other in enumerate(others):
            lo = (1 - t) * start[slot][0] + t * end[slot][0]
            hi = (1 - t) * start[slot][1] + t * end[slot][1]
            vertices[k, other] = lo + corner[other] * (hi - lo)
    return trimesh.Trimesh(vertices=vertices, faces=unit.faces, process=False)


def band(curve: NDArray[np.float64], thickness: float, y: Interval) -> trimesh.Trimesh:
    """A vertical sheet following a curve in the floor plane, `thickness` thick along x.

    `curve` is (n, 2) of (x, z) with z increasing; the sheet spans curve x +- thickness/2
    (a curtain's folds).
    """
    _check("y", y)
    curve = np.asarray(curve, dtype=float)
    n = len(curve)
    half = np.array([thickness / 2.0, 0.0])
    back, front = curve - half, curve + half
    # Plane coordinates (x, -z): the z->y rotation below maps them back onto (x, z).
    outline = np.vstack([back, front]) * [1.0, -1.0]
    i = np.arange(n - 1)
    quads = np.column_stack([i, i + 1, n + i + 1, n + i])
    triangles = np.vstack([quads[:, [0, 1, 2]], quads[:, [0, 2, 3]]])
    mesh = trimesh.creation.extrude_triangulation(outline, triangles, height=y[1] - y[0])
    mesh.apply_transform(_Z_TO_Y)
    mesh.apply_translation([0.0, y[0], 0.0])
    return mesh


def superellipsoid(
    x: Interval, y: Interval, z: Interval, squareness: float, pinch: float
) -> trimesh.Trimesh:
    """A rounded block filling the box, thinner towards its rim (a pillow or cushion).

    squareness in (0, 1]: 1 is an ellipsoid, small values are boxy; pinch in [0, 1) thins
    the rim to (1 - pinch) of the centre height.
    """
    for name, interval in (("x", x), ("y", y), ("z", z)):
        _check(name, interval)
    sphere = trimesh.creation.icosphere(subdivisions=2)
    v = sphere.vertices
    v = np.sign(v) * np.abs(v) ** squareness
    rim = np.maximum(np.abs(v[:, 0]), np.abs(v[:, 2]))
    v[:, 1] *= 1.0 - pinch * rim**2
    lo = np.array([x[0], y[0], z[0]])
    hi = np.array([x[1], y[1], z[1]])
    span = v.max(axis=0) - v.min(axis=0)
    vertices = lo + (v - v.min(axis=0)) / span * (hi - lo)
    return trimesh.Trimesh(vertices=vertices, faces=sphere.faces, process=False)


def turned_to_x(mesh: trimesh.Trimesh) -> trimesh.Trimesh:
    """Rotate a mesh built about the vertical axis so that axis points along +x.

    (x, y, z) -> (y, -x, z): build with radii (ry, rz) and "heights" that are x positions
    (an oval mirror facing +x).
    """
    mesh.apply_transform(trimesh.transformations.rotation_matrix(-np.pi / 2, [0.0, 0.0, 1.0]))
    return mesh
