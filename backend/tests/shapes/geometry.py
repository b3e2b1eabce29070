"""Test helpers: per-part meshes and a brute-force ray cast (no Embree needed)."""

from __future__ import annotations

import numpy as np
import trimesh
from holiscene.shapes import Shape
from numpy.typing import NDArray


def part_meshes(shape: Shape) -> list[trimesh.Trimesh]:
    """Each part of a shape as its own mesh (sharing the shape's vertex array)."""
    return [
        trimesh.Trimesh(shape.mesh.vertices, shape.mesh.faces[shape.face_part == i], process=False)
        for i in range(len(shape.parts))
    ]


def ray_distances(
    mesh: trimesh.Trimesh, origin: NDArray[np.float64], direction: NDArray[np.float64]
) -> NDArray[np.float64]:
    """Sorted distances along a unit ray to every triangle it crosses (Moller-Trumbore)."""
    triangles = np.asarray(mesh.triangles, dtype=float)
    v0, edge1, edge2 = (
        triangles[:, 0],
        triangles[:, 1] - triangles[:, 0],
        triangles[:, 2] - triangles[:, 0],
    )
    p = np.cross(direction, edge2)
    det = np.einsum("ij,ij->i", edge1, p)
    ok = np.abs(det) > 1e-15
    inv = np.where(ok, 1.0 / np.where(ok, det, 1.0), 0.0)
    s = origin - v0
    u = np.einsum("ij,ij->i", s, p) * inv
    q = np.cross(s, edge1)
    v = (q @ direction) * inv
    t = np.einsum("ij,ij->i", edge2, q) * inv
    hit = ok & (u >= -1e-12) & (v >= -1e-12) & (u + v <= 1 + 1e-12) & (t > 0)
    return np.sort(t[hit])
