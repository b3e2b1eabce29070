"""Training samples for the mesh network: one library object seen as a room camera sees it.

Each sample is a random class, size and library variant (the truth), its silhouette from a
random viewpoint at a person's eye height (rasterised, then cut as occluders and imperfect
masks cut it), and its class template to deform. The truth is kept as dense surface points in
the box's normalised frame; the template's own surface samples are stored as barycentric
weights of its vertices, so the deformed mesh's samples follow its vertices.
"""

from __future__ import annotations

from dataclasses import dataclass

import cv2
import numpy as np
import trimesh
from numpy.typing import NDArray

from ...shapes import generate_shape, typical_size
from ..budget import collect_samples, stack_fields
from .inputs import (
    MAX_TEMPLATE_VERTICES,
    MESH_CLASSES,
    VERTEX_FEATURES,
    FloatArray,
    condition_vector,
    silhouette_input,
    surface_samples,
    template,
)

TRUTH_POINTS = 2048
TEMPLATE_SAMPLES = 1024
MIN_MASK_PIXELS = 40
_IMAGE = (640, 480)
# Classes that are usually seen above the floor (on a wall, a bed or a shelf).
_RAISED = frozenset(
    {"picture", "window", "mirror", "television", "pillow", "books", "box", "lamp", "sink"}
)


@dataclass(frozen=True)
class MeshSample:
    silhouette: FloatArray  # (S, S)
    condition: FloatArray  # (CONDITION_SIZE,)
    template: FloatArray  # (MAX_TEMPLATE_VERTICES, VERTEX_FEATURES), zero-padded
    vertex_count: int
    sample_vertices: NDArray[np.int32]  # (TEMPLATE_SAMPLES, 3)
    sample_weights: FloatArray  # (TEMPLATE_SAMPLES, 3)
    truth: FloatArray  # (TRUTH_POINTS, 3), normalised box frame
    scale: FloatArray  # (3,) normalised frame -> eval frame (size / longest side)


def _look_at(eye: NDArray[np.float64], target: NDArray[np.float64]) -> NDArray[np.float64]:
    """Rows: the camera's right, down and forward axes in the world (y up)."""
    forward = target - eye
    forward /= np.linalg.norm(forward)
    right = np.cross(forward, [0.0, 1.0, 0.0])
    right /= max(np.linalg.norm(right), 1e-9)
    down = np.cross(forward, right)
    return np.stack([right, down, forward])


def _random_view(
    size: NDArray[np.float64], raised: bool, rng: np.random.Generator
) -> tuple[NDArray[np.float64], NDArray[np.float64], float]:
    """A camera (position, rotation rows, focal length) around an object centred at the origin."""
    floor = -size[1] / 2 - (rng.uniform(0.3, 1.3) if raised else 0.0)
    front = rng.random() < 0.8  # objects mostly stand against walls, seen from their front half
    azimuth = rng.uniform(-1.75, 1.75) if front else rng.uniform(-np.pi, np.pi)
    distance = 0.5 * float(np.linalg.norm(size)) + rng.uniform(0.8, 4.5)
    eye = np.array(
        [distance * np.cos(azimuth), floor + rng.uniform(1.0, 1.9), distance * np.sin(azimuth)]
    )
    target = rng.normal(0.0, 0.25, 3) * np.array([1.0, 0.5, 1.0])
    return eye, _look_at(eye, target), float(rng.uniform(430.0, 720.0))


def _rasterise(
    vertices: NDArray[np.float64],
    faces: NDArray[np.int64],
    eye: NDArray[np.float64],
    rotation: NDArray[np.float64],
    focal: float,
) -> NDArray[np.bool_] | None:
    camera = (vertices - eye) @ rotation.T
    if camera[:, 2].min() < 0.1:
        return None
    width, height = _IMAGE
    pixels = focal * camera[:, :2] / camera[:, 2:3] + np.array([width / 2, height / 2])
    canvas = np.zeros((height, width), dtype=np.uint8)
    # One triangle at a time: fillPoly over many contours would cancel where they overlap.
    for triangle in np.round(pixels[faces] * 16).astype(np.int32):
        cv2.fillConvexPoly(canvas, triangle, 1, cv2.LINE_8, 4)
    return canvas.astype(bool)


def _imperfect(mask: NDArray[np.bool_], rng: np.random.Generator) -> NDArray[np.bool_]:
    """The mask as the pipeline would see it: partly hidden by an occluder, ragged edges."""
    rows, cols = np.flatnonzero(mask.any(axis=1)), np.flatnonzero(mask.any(axis=0))
    out = mask.copy()
    if rng.random() < 0.4:
        side = rng.choice(4, p=[0.55, 0.15, 0.15, 0.15])  # bottom, left, right, top
        lo, hi = (rows[0], rows[-1]) if side in (0, 3) else (cols[0], cols[-1])
        cut = int((hi - lo) * rng.uniform(0.1, 0.45))
        if side == 0:
            out[hi - cut :] = False
        elif side == 3:
            out[: lo + cut] = False
        elif side == 1:
            out[:, : lo + cut] = False
        else:
            out[:, hi - cut :] = False
    if rng.random() < 0.5:
        kernel = np.ones((3, 3), np.uint8)
        operation = cv2.MORPH_OPEN if rng.random() < 0.5 else cv2.MORPH_CLOSE
        out = cv2.morphologyEx(out.astype(np.uint8), operation, kernel).astype(bool)
    return out


def make_sample(rng: np.random.Generator) -> MeshSample | None:
    """One sample (None when the view missed the object)."""
    cls = MESH_CLASSES[int(rng.integers(len(MESH_CLASSES)))]
    size_tuple = typical_size(cls, rng)
    size = np.asarray(size_tuple, dtype=float)
    truth_mesh = generate_shape(cls, size_tuple, rng).mesh
    eye, rotation, focal = _random_view(size, cls in _RAISED, rng)
    full = _rasterise(np.asarray(truth_mesh.vertices), truth_mesh.faces, eye, rotation, focal)
    if full is None or full.sum() < MIN_MASK_PIXELS:
        return None
    mask = _imperfect(full, rng)
    if mask.sum() < MIN_MASK_PIXELS:
        return None
    shape_template = template(cls, size_tuple)
    count = len(shape_template.vertices)
    padded = np.zeros((MAX_TEMPLATE_VERTICES, VERTEX_FEATURES), dtype=np.float32)
    padded[:count] = shape_template.vertices
    indices, weights = surface_samples(
        shape_template.faces, shape_template.vertices, TEMPLATE_SAMPLES, rng
    )
    truth = trimesh.sample.sample_surface(truth_mesh, TRUTH_POINTS, seed=int(rng.integers(2**31)))
    return MeshSample(
        silhouette=silhouette_input(mask),
        condition=condition_vector(cls, size_tuple, -eye),
        template=padded,
        vertex_count=count,
        sample_vertices=indices.astype(np.int32),
        sample_weights=weights,
        truth=(truth[0] / size).astype(np.float32),
        scale=(size / size.max()).astype(np.float32),
    )


def make_samples(count: int, seed: int, progress: bool = True) -> dict[str, np.ndarray]:
    """`count` samples stacked into arrays named as MeshSample's fields."""
    rows = collect_samples(count, make_sample, seed, "view", progress)
    return stack_fields(rows, MeshSample.__dataclass_fields__)
