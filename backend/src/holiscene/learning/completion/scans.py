"""Training pairs for shape completion: a library mesh, a noisy partial scan of it, and targets.

A scan is a depth render of the one mesh from a random viewpoint, back-projected (every pixel's
first hit along its ray, Embree), with depth noise that grows with distance like a structured-
light sensor's, a few dropped pixels and a few stray points. Targets are dense surface samples
and meso-skeleton points: each part of the parametric shape collapsed onto its medial curve
(rod-like parts: the main axis) or medial sheet (board-like and bulky parts: the mid-plane
across the thinnest axis), then spread evenly by farthest point sampling.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import trimesh
from numpy.typing import NDArray

from ...shapes import SUPPORTED_CLASSES, Shape, generate_shape, typical_size
from ...synth.raycast import MISS, RayCaster
from ..budget import collect_samples, stack_fields

FloatArray = NDArray[np.float32]

PARTIAL_POINTS = 512  # points the network reads
SURFACE_POINTS = 2048  # dense surface target
SKELETON_POINTS = 128  # meso-skeleton target (K)
_SCAN_PIXELS = 48  # the square depth image rendered around the object
_MIN_HITS = 24
# Observed points farther out of the box than this (normalised) are someone else's: dropped.
KEEP_BOUND = 0.65


@dataclass(frozen=True)
class CompletionSample:
    partial: FloatArray  # (PARTIAL_POINTS, 3), normalised object frame
    surface: FloatArray  # (SURFACE_POINTS, 3)
    skeleton: FloatArray  # (SKELETON_POINTS, 3)


def normalise(points: NDArray[np.float64], size: NDArray[np.float64]) -> FloatArray:
    """Points of the box's local frame (metres, centred) in the unit cube of the box."""
    result: FloatArray = (points / size).astype(np.float32)
    return result


def resample(points: NDArray[np.floating], count: int, rng: np.random.Generator) -> FloatArray:
    """Exactly `count` points: a random subset, or every point plus random repeats."""
    n = len(points)
    if n >= count:
        index = rng.choice(n, count, replace=False)
    else:
        index = np.concatenate([np.arange(n), rng.choice(n, count - n, replace=True)])
    result: FloatArray = np.asarray(points[index], dtype=np.float32)
    return result


def farthest_points(points: NDArray[np.float64], count: int) -> NDArray[np.float64]:
    """`count` points spread evenly over `points` (greedy farthest point sampling)."""
    chosen = [0]
    distance = np.linalg.norm(points - points[0], axis=1)
    for _ in range(1, min(count, len(points))):
        chosen.append(int(np.argmax(distance)))
        distance = np.minimum(distance, np.linalg.norm(points - points[chosen[-1]], axis=1))
    result: NDArray[np.float64] = points[chosen]
    return result


def skeleton_points(shape: Shape, count: int, rng: np.random.Generator) -> NDArray[np.float64]:
    """Meso-skeleton of a shape in its canonical frame: each part collapsed to a curve or sheet."""
    samples, faces = trimesh.sample.sample_surface(shape.mesh, 6000, seed=int(rng.integers(2**31)))
    part_of = shape.face_part[faces]
    collapsed = []
    for part in np.unique(part_of):
        points = samples[part_of == part]
        if len(points) < 4:
            continue
        centre = points.mean(axis=0)
        _, spread, axes = np.linalg.svd(points - centre, full_matrices=False)
        coords = (points - centre) @ axes.T
        # A rod keeps only its main axis; a board or block keeps its two widest axes.
        keep = 1 if spread[1] < 0.35 * spread[0] else 2
        coords[:, keep:] = 0.0
        collapsed.append(centre + coords @ axes)
    return farthest_points(np.vstack(collapsed), count)


def _view_rays(
    extent: NDArray[np.float64], rng: np.random.Generator
) -> tuple[NDArray[np.float64], NDArray[np.float64], NDArray[np.float64]]:
    """A random camera looking at the box's centre: ray origins, unit directions, its axis."""
    azimuth = rng.uniform(-np.pi, np.pi)
    elevation = rng.uniform(-0.1, 0.8)  # mostly from above, as a room camera sees furniture
    axis = -np.array(
        [
            np.cos(elevation) * np.cos(azimuth),
            np.sin(elevation),
            np.cos(elevation) * np.sin(azimuth),
        ]
    )
    radius = 0.5 * float(np.linalg.norm(extent))
    distance = radius + rng.uniform(1.0, 4.5)
    eye = -axis * distance
    right = np.cross(axis, [0.0, 1.0, 0.0])
    right /= max(np.linalg.norm(right), 1e-9)
    up = np.cross(right, axis)
    half = np.arctan2(radius * 1.05, distance)
    ticks = np.tan(np.linspace(-half, half, _SCAN_PIXELS))
    u, v = np.meshgrid(ticks, ticks)
    directions = axis + u.reshape(-1, 1) * right + v.reshape(-1, 1) * up
    directions /= np.linalg.norm(directions, axis=1, keepdims=True)
    return np.broadcast_to(eye, directions.shape), directions, axis


def partial_scan(mesh: trimesh.Trimesh, rng: np.random.Generator) -> NDArray[np.float64] | None:
    """Back-projected depth of `mesh` seen from a random view, with sensor-like noise."""
    extent = mesh.bounds[1] - mesh.bounds[0]
    origins, directions, axis = _view_rays(extent, rng)
    faces, distance = RayCaster(mesh.vertices, mesh.faces).first_hits(origins, directions)
    hit = (faces != MISS) & (rng.random(len(faces)) > rng.uniform(0.0, 0.3))
    if hit.sum() < _MIN_HITS:
        return None
    depth = distance[hit] * (directions[hit] @ axis)  # along the optical axis, as a sensor reports
    noisy = depth + rng.normal(0.0, 0.0015 + 0.0025 * depth**2)
    points = origins[hit] + directions[hit] * (noisy / (directions[hit] @ axis))[:, None]
    stray = rng.random(len(points)) < 0.02  # flying pixels at silhouettes
    points[stray] += rng.normal(0.0, 0.1, (int(stray.sum()), 3)) * extent
    result: NDArray[np.float64] = points
    return result


def make_sample(rng: np.random.Generator) -> CompletionSample | None:
    """One training pair from a random class, size and viewpoint (None: the view saw too little)."""
    classes = (*SUPPORTED_CLASSES, "otherprop")
    cls = classes[int(rng.integers(len(classes)))]
    size = np.array(typical_size(cls, rng))
    shape = generate_shape(cls, (size[0], size[1], size[2]), rng)
    scan = partial_scan(shape.mesh, rng)
    if scan is None:
        return None
    partial = normalise(scan, size)
    partial = partial[np.abs(partial).max(axis=1) <= KEEP_BOUND]
    if len(partial) < _MIN_HITS:
        return None
    surface = trimesh.sample.sample_surface(
        shape.mesh, SURFACE_POINTS, seed=int(rng.integers(2**31))
    )[0]
    return CompletionSample(
        partial=resample(partial, PARTIAL_POINTS, rng),
        surface=normalise(surface, size),
        skeleton=normalise(skeleton_points(shape, SKELETON_POINTS, rng), size),
    )


def make_samples(count: int, seed: int, progress: bool = True) -> dict[str, FloatArray]:
    """`count` pairs stacked into arrays `partial`, `surface`, `skeleton`."""
    rows = collect_samples(count, make_sample, seed, "scan", progress)
    return stack_fields(rows, ("partial", "surface", "skeleton"))
