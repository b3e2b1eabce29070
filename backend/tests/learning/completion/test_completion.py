"""Shape completion: training scans of the library, the voxel mesher, and the committed ONNX
model at run time."""

from __future__ import annotations

import math

import numpy as np
import pytest
import trimesh
from holiscene.evaluation.shape_metrics import chamfer_distance
from holiscene.geometry.camera import rot_y
from holiscene.learning.completion.meshing import RESOLUTION, mesh_from_points
from holiscene.learning.completion.runtime import (
    MIN_OBSERVED_POINTS,
    completer,
    to_box_frame,
)
from holiscene.learning.completion.scans import (
    PARTIAL_POINTS,
    SKELETON_POINTS,
    SURFACE_POINTS,
    make_sample,
    partial_scan,
    skeleton_points,
)
from holiscene.shapes import generate_shape
from holiscene_schema import Box3D


def test_a_scan_sees_one_side_of_the_mesh_and_lies_on_it() -> None:
    rng = np.random.default_rng(3)
    box = trimesh.creation.box(extents=[1.0, 1.0, 1.0])
    scan = partial_scan(box, rng)
    assert scan is not None and len(scan) > 200
    reach = np.abs(scan).max(axis=1)  # the unit cube's surface is where this is 0.5
    assert np.median(np.abs(reach - 0.5)) < 0.04  # a sensor's noise at 2-5 m, a few stray points
    # Seen from one side: at most three faces of a cube hold points, never all six.
    axis = np.abs(scan).argmax(axis=1)
    face = axis * 2 + (scan[np.arange(len(scan)), axis] > 0)
    share = np.bincount(face, minlength=6) / len(scan)
    assert (share > 0.05).sum() <= 3


def test_a_chairs_skeleton_runs_inside_its_parts() -> None:
    shape = generate_shape("chair", (0.5, 0.9, 0.5), np.random.default_rng(0))
    skeleton = skeleton_points(shape, SKELETON_POINTS, np.random.default_rng(1))
    assert skeleton.shape == (SKELETON_POINTS, 3)
    inside = shape.mesh.contains(skeleton)
    assert inside.mean() > 0.8  # medial curves and sheets of closed parts are inside them


def test_training_samples_have_the_networks_shapes_in_the_unit_box() -> None:
    rng = np.random.default_rng(5)
    sample = None
    while sample is None:
        sample = make_sample(rng)
    assert sample.partial.shape == (PARTIAL_POINTS, 3)
    assert sample.surface.shape == (SURFACE_POINTS, 3)
    assert np.abs(sample.surface).max() <= 0.5 + 1e-5
    assert np.abs(sample.partial).max() <= 0.65


def test_the_mesher_makes_a_solid_close_to_the_points() -> None:
    box = trimesh.creation.box(extents=[0.6, 0.8, 0.4])
    points = trimesh.sample.sample_surface(box, 3000, seed=0)[0]
    mesh = mesh_from_points(points)
    assert mesh.volume == pytest.approx(box.volume, rel=0.35)  # filled, not a hollow shell
    surface = trimesh.sample.sample_surface(mesh, 3000, seed=1)[0]
    assert chamfer_distance(surface, points) < 1.0 / RESOLUTION


def test_the_committed_model_completes_a_scan_in_the_world() -> None:
    rng = np.random.default_rng(11)
    size = (0.55, 0.85, 0.5)
    shape = generate_shape("chair", size, rng)
    box = Box3D(center=[3.0, -0.8, 0.5], size=list(size), yaw_deg=30.0)
    scan = None
    while scan is None:
        scan = partial_scan(shape.mesh, rng)
    # The scan in the world, as depth back-projection gives it.
    turn = rot_y(math.radians(30.0))
    world = scan @ turn.T + np.asarray(box.center)
    assert np.allclose(to_box_frame(world, box), scan / np.asarray(size), atol=1e-9)
    result = completer().complete(world, box)
    assert result is not None
    local = to_box_frame(np.asarray(result.mesh.vertices), box)
    assert np.abs(local).max() < 0.75  # the mesh stays around its box
    truth = trimesh.sample.sample_surface(shape.mesh, 2048, seed=0)[0] @ turn.T + box.center
    completed = trimesh.sample.sample_surface(result.mesh, 2048, seed=0)[0]
    # Completeness: the true surface is nearer the completed mesh than the one-sided scan.
    assert _coverage(truth, completed) < 0.7 * _coverage(truth, world)


def _coverage(truth: np.ndarray, points: np.ndarray) -> float:
    """Mean distance from each true surface point to the nearest of `points`."""
    return float(np.linalg.norm(truth[:, None] - points[None], axis=2).min(axis=1).mean())


def test_too_few_points_in_the_box_give_no_completion() -> None:
    box = Box3D(center=[2.0, 0.0, 0.0], size=[0.5, 0.5, 0.5], yaw_deg=0.0)
    far = np.random.default_rng(0).normal([5.0, 0.0, 0.0], 0.1, (500, 3))
    assert completer().complete(far, box) is None
    near = np.random.default_rng(0).uniform(1.9, 2.1, (MIN_OBSERVED_POINTS - 1, 3))
    assert completer().complete(near, box) is None


def test_the_mesher_smooths_the_voxel_staircase() -> None:
    # On a ball the surface normals should point away from the centre; a voxel surface's
    # normals point along the grid's axes instead (about 0.6 on average).
    ball = trimesh.creation.icosphere(subdivisions=3, radius=0.4)
    points = trimesh.sample.sample_surface(ball, 4000, seed=0)[0]
    mesh = mesh_from_points(points)
    centres = mesh.triangles_center
    radial = centres / np.linalg.norm(centres, axis=1, keepdims=True)
    alignment = float(np.einsum("ij,ij->i", mesh.face_normals, radial).mean())
    assert alignment > 0.9
