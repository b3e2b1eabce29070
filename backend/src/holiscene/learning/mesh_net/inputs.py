"""What the mesh network reads about one object, the same in training and at run time.

- `silhouette`: the object's mask cropped to its own bounds, padded to a square around its
  centre (so the crop keeps its aspect) and shrunk to SILHOUETTE_PIXELS.
- `condition`: the class (one-hot over MESH_CLASSES), the box's proportions (size over its
  longest side) and the viewing direction (camera to box centre, a unit vector in the box's
  frame: x front, y up, z right).
- `template`: the class's template mesh (library variant 0 at the box's size), subdivided so
  that parts can bend, its vertices in the box's normalised frame ([-0.5, 0.5]^3), each with
  the centre and half extent of the part it belongs to (VERTEX_FEATURES numbers a vertex):
  the part tells the network which vertices move together (a leg, the seat).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from functools import lru_cache

import cv2
import numpy as np
import trimesh
from numpy.typing import NDArray

from ...geometry.camera import rot_y
from ...shapes import SUPPORTED_CLASSES, generate_shape

FloatArray = NDArray[np.float32]

SILHOUETTE_PIXELS = 48
MESH_CLASSES: tuple[str, ...] = SUPPORTED_CLASSES
CONDITION_SIZE = len(MESH_CLASSES) + 6
MAX_TEMPLATE_VERTICES = 640
VERTEX_FEATURES = 9  # position, its part's centre, its part's half extent
# Longest template edge after subdivision, in the normalised box (coarser when over the cap).
_TEMPLATE_EDGES = (0.2, 0.3, 0.45, 0.7)


def silhouette_input(mask: NDArray[np.bool_]) -> FloatArray:
    """The mask's square crop around its bounds, SILHOUETTE_PIXELS on a side, values 0..1."""
    rows, cols = np.flatnonzero(mask.any(axis=1)), np.flatnonzero(mask.any(axis=0))
    if len(rows) == 0:
        raise ValueError("empty mask")
    y0, y1, x0, x1 = int(rows[0]), int(rows[-1]) + 1, int(cols[0]), int(cols[-1]) + 1
    side = max(y1 - y0, x1 - x0)
    canvas = np.zeros((side, side), dtype=np.float32)
    oy, ox = (side - (y1 - y0)) // 2, (side - (x1 - x0)) // 2
    canvas[oy : oy + y1 - y0, ox : ox + x1 - x0] = mask[y0:y1, x0:x1]
    size = (SILHOUETTE_PIXELS, SILHOUETTE_PIXELS)
    result: FloatArray = cv2.resize(canvas, size, interpolation=cv2.INTER_AREA).astype(np.float32)
    return result


def condition_vector(
    cls: str, size: tuple[float, float, float], view_direction: NDArray[np.float64]
) -> FloatArray:
    """Class one-hot, proportions and the unit viewing direction in the box's frame."""
    vector = np.zeros(CONDITION_SIZE, dtype=np.float32)
    vector[MESH_CLASSES.index(cls)] = 1.0
    extent = np.asarray(size, dtype=float)
    vector[len(MESH_CLASSES) : len(MESH_CLASSES) + 3] = extent / extent.max()
    direction = np.asarray(view_direction, dtype=float)
    vector[len(MESH_CLASSES) + 3 :] = direction / max(float(np.linalg.norm(direction)), 1e-9)
    return vector


def view_direction(
    camera_position: NDArray[np.float64], centre: NDArray[np.float64], yaw_deg: float
) -> NDArray[np.float64]:
    """Camera-to-centre direction in the frame of a box with this yaw."""
    direction = np.asarray(centre, dtype=float) - np.asarray(camera_position, dtype=float)
    local: NDArray[np.float64] = direction @ rot_y(math.radians(yaw_deg))
    return local / max(float(np.linalg.norm(local)), 1e-9)


@dataclass(frozen=True)
class Template:
    vertices: FloatArray  # (V, VERTEX_FEATURES): normalised position, part centre, half extent
    faces: NDArray[np.int64]  # (F, 3)

    @property
    def positions(self) -> FloatArray:
        result: FloatArray = self.vertices[:, :3]
        return result


def template(cls: str, size: tuple[float, float, float]) -> Template:
    """The class's template at this box size, subdivided, at most MAX_TEMPLATE_VERTICES."""
    d, h, w = (round(float(s), 3) for s in size)  # rounded: a cache key
    return _template(cls, (d, h, w))


@lru_cache(maxsize=512)
def _template(cls: str, size: tuple[float, float, float]) -> Template:
    shape = generate_shape(cls, size, np.random.default_rng(0))
    vertices = np.asarray(shape.mesh.vertices, dtype=float) / np.asarray(size, dtype=float)
    faces = np.asarray(shape.mesh.faces, dtype=np.int64)
    best = (vertices, faces, np.arange(len(faces)))
    for edge in _TEMPLATE_EDGES:
        finer = trimesh.remesh.subdivide_to_size(  # type: ignore[no-untyped-call]
            vertices, faces, max_edge=edge, max_iter=6, return_index=True
        )
        if len(finer[0]) <= MAX_TEMPLATE_VERTICES:
            best = finer
            break
    positions, new_faces, source_face = best
    # Parts share no vertex (shapes.Shape), so each vertex belongs to exactly one part.
    vertex_part = np.zeros(len(positions), dtype=np.int64)
    vertex_part[new_faces.ravel()] = np.repeat(shape.face_part[source_face], 3)
    features = np.zeros((len(positions), VERTEX_FEATURES))
    features[:, :3] = positions
    for part in np.unique(vertex_part):
        members = vertex_part == part
        lo, hi = positions[members].min(axis=0), positions[members].max(axis=0)
        features[members, 3:6] = (lo + hi) / 2
        features[members, 6:9] = (hi - lo) / 2
    return Template(features.astype(np.float32), np.asarray(new_faces, dtype=np.int64))


def surface_samples(
    faces: NDArray[np.int64], vertices: NDArray[np.floating], count: int, rng: np.random.Generator
) -> tuple[NDArray[np.int64], FloatArray]:
    """`count` points on a mesh as (vertex indices (count, 3), barycentric weights (count, 3)),
    area-weighted: a deformed mesh's samples are then the same weights of its moved vertices."""
    corners = np.asarray(vertices, dtype=float)[:, :3][faces]
    area = 0.5 * np.linalg.norm(
        np.cross(corners[:, 1] - corners[:, 0], corners[:, 2] - corners[:, 0]), axis=1
    )
    chosen = rng.choice(len(faces), count, p=area / area.sum())
    u, v = rng.random(count), rng.random(count)
    flip = u + v > 1
    u[flip], v[flip] = 1 - u[flip], 1 - v[flip]
    weights = np.stack([1 - u - v, u, v], axis=1).astype(np.float32)
    return faces[chosen], weights
