"""The mesh network: its inputs, its training samples and a short training run, face cutting,
and the committed ONNX model placing a mesh that matches a rendered object's silhouette."""

from __future__ import annotations

import json
import math
from pathlib import Path

import numpy as np
import pytest
import trimesh
from holiscene.geometry.camera import PinholeCamera, rot_y
from holiscene.learning.mesh_net.inputs import (
    CONDITION_SIZE,
    MAX_TEMPLATE_VERTICES,
    MESH_CLASSES,
    SILHOUETTE_PIXELS,
    VERTEX_FEATURES,
    condition_vector,
    silhouette_input,
    surface_samples,
    template,
    view_direction,
)
from holiscene.learning.mesh_net.runtime import MODEL_DIR, MeshGenerator, cut_faces
from holiscene.learning.mesh_net.samples import TEMPLATE_SAMPLES, TRUTH_POINTS, make_samples
from holiscene.placement.projection import MaskTarget
from holiscene.placement.room import projection_matrix
from holiscene.shapes import generate_shape
from holiscene_schema import Box3D


def test_the_silhouette_keeps_its_aspect_centred_in_the_square() -> None:
    mask = np.zeros((100, 200), dtype=bool)
    mask[40:60, 50:150] = True  # 100 wide, 20 high
    square = silhouette_input(mask)
    assert square.shape == (SILHOUETTE_PIXELS, SILHOUETTE_PIXELS)
    rows = np.flatnonzero(square.max(axis=1) > 0.5)
    assert square[:, 0].max() > 0.5 and square[:, -1].max() > 0.5  # full width
    assert 8 <= len(rows) <= 11  # a fifth of the height
    assert abs(rows.mean() - (SILHOUETTE_PIXELS - 1) / 2) < 1.0
    with pytest.raises(ValueError, match="empty"):
        silhouette_input(np.zeros((5, 5), dtype=bool))


def test_the_condition_holds_class_proportions_and_a_unit_direction() -> None:
    vector = condition_vector("chair", (0.5, 1.0, 0.4), np.array([3.0, -1.0, 0.0]))
    assert vector.shape == (CONDITION_SIZE,)
    assert vector[: len(MESH_CLASSES)].sum() == 1.0
    assert vector[MESH_CLASSES.index("chair")] == 1.0
    np.testing.assert_allclose(vector[len(MESH_CLASSES) : len(MESH_CLASSES) + 3], [0.5, 1.0, 0.4])
    assert math.isclose(float(np.linalg.norm(vector[-3:])), 1.0, rel_tol=1e-6)


def test_the_view_direction_turns_with_the_box() -> None:
    centre = np.array([0.0, -1.0, 3.0])
    straight = view_direction(np.zeros(3), centre, 0.0)
    turned = view_direction(np.zeros(3), centre, 90.0)
    np.testing.assert_allclose(straight, centre / np.linalg.norm(centre))
    # In a box turned by 90 degrees the ray comes in along its x axis instead of its z.
    np.testing.assert_allclose(turned, rot_y(math.radians(90.0)).T @ straight, atol=1e-9)
    assert abs(turned[0]) > 0.9


def test_templates_are_capped_subdivided_and_fill_the_unit_box() -> None:
    for cls in ("chair", "bed", "picture", "lamp"):
        shape = template(cls, (0.5, 0.9, 0.5))
        raw = generate_shape(cls, (0.5, 0.9, 0.5), np.random.default_rng(0)).mesh
        assert len(raw.vertices) < len(shape.vertices) <= MAX_TEMPLATE_VERTICES
        assert shape.vertices.shape[1] == VERTEX_FEATURES
        np.testing.assert_allclose(shape.positions.min(axis=0), -0.5, atol=1e-5)
        np.testing.assert_allclose(shape.positions.max(axis=0), 0.5, atol=1e-5)
        # Every vertex lies in its part's box, and parts are smaller than the whole.
        centre, half = shape.vertices[:, 3:6], shape.vertices[:, 6:9]
        assert np.all(np.abs(shape.positions - centre) <= half + 1e-5)
        assert len(np.unique(centre, axis=0)) > 1


def test_surface_samples_spread_over_the_template_by_area() -> None:
    shape = template("table", (0.8, 0.7, 1.2))
    rng = np.random.default_rng(1)
    indices, weights = surface_samples(shape.faces, shape.vertices, 20000, rng)
    assert indices.shape == weights.shape == (20000, 3)
    assert np.all(weights >= 0) and np.allclose(weights.sum(axis=1), 1.0, atol=1e-6)
    points = (shape.positions[indices] * weights[..., None]).sum(axis=1)
    assert np.all(np.abs(points) <= 0.5 + 1e-6)
    # The table top (the highest faces) holds its share of the area, not of the face count.
    mesh = trimesh.Trimesh(shape.positions, shape.faces, process=False)
    top = shape.positions[shape.faces][:, :, 1].min(axis=1) > 0.5 - 1e-4
    share = mesh.area_faces[top].sum() / mesh.area
    assert abs(np.mean(points[:, 1] > 0.5 - 1e-4) - share) < 0.02


def test_training_samples_have_the_networks_shapes() -> None:
    data = make_samples(12, seed=5, progress=False)
    assert data["silhouette"].shape == (12, SILHOUETTE_PIXELS, SILHOUETTE_PIXELS)
    assert data["template"].shape == (12, MAX_TEMPLATE_VERTICES, VERTEX_FEATURES)
    assert data["sample_vertices"].shape == (12, TEMPLATE_SAMPLES, 3)
    assert data["truth"].shape == (12, TRUTH_POINTS, 3)
    assert np.all(data["silhouette"].reshape(12, -1).max(axis=1) > 0.5)
    assert np.abs(data["truth"]).max() <= 0.5 + 1e-5
    assert np.all(data["sample_vertices"].max(axis=(1, 2)) < data["vertex_count"])
    np.testing.assert_allclose(data["scale"].max(axis=1), 1.0)


def test_cutting_keeps_the_faces_expected_close_but_never_less_than_the_floor() -> None:
    faces = np.array([[0, 1, 2], [1, 2, 3], [2, 3, 4], [3, 4, 5]])
    error = np.array([0.0, 0.0, 0.01, 0.02, 0.5, 0.6])
    np.testing.assert_array_equal(cut_faces(faces, error, 0.05, 0.25), faces[:2])
    assert len(cut_faces(faces, error, 0.001, 0.5)) == 2  # half kept at worst
    assert len(cut_faces(faces, error, 1.0, 0.5)) == 4


def test_a_short_training_run_exports_an_onnx_model_equal_to_pytorch(tmp_path: Path) -> None:
    pytest.importorskip("torch")
    from holiscene.learning.mesh_net.train import CUT_CHOICES, MeshNetTraining, train_mesh_net

    run = MeshNetTraining(
        out=tmp_path / "model", train_views=24, validation_views=8, time_budget=3.0, batch=4
    )
    metrics = train_mesh_net(run)
    assert metrics["onnx_max_abs_difference"] < 1e-3
    assert metrics["cut_chamfer"] <= metrics["moved_chamfer"] + 1e-9
    metadata = json.loads((tmp_path / "model" / "metadata.json").read_text())
    assert metadata["classes"] == list(MESH_CLASSES)
    assert (tmp_path / "model" / "curve.png").stat().st_size > 1000
    generator = MeshGenerator(tmp_path / "model")
    threshold = metadata["cut_threshold"]
    assert generator.cut_threshold == (math.inf if threshold is None else threshold)
    assert set(metadata["cut_chamfer"]) == {str(t) for t in CUT_CHOICES}


def _rendered_chair() -> tuple[Box3D, np.ndarray, np.ndarray]:
    """A chair 2.5 m in front of a level camera, its front turned towards it, and its mask."""
    width, height = 640, 480
    camera = PinholeCamera(np.array([[520.0, 0, 320], [0, 520.0, 240], [0, 0, 1]]), 0.0, 0.0)
    axis = camera.optical_axis
    centre = axis * 2.5 + np.array([0.0, -0.9, 0.0])
    # The quarter turn whose front (local +x) looks back at the camera.
    yaw = min(
        (0.0, 90.0, 180.0, 270.0),
        key=lambda y: float(rot_y(math.radians(y))[:, 0] @ axis),
    )
    box = Box3D(center=tuple(centre), size=(0.55, 0.95, 0.5), yaw_deg=yaw)
    chair = generate_shape("chair", box.size, np.random.default_rng(7)).mesh
    world = np.asarray(chair.vertices) @ rot_y(math.radians(yaw)).T + centre
    projection = projection_matrix(camera)
    full = np.ones((height, width), dtype=bool)
    target = MaskTarget(full, max_side=max(width, height), margin=0.0, min_pad=0)
    silhouette = target.silhouette(projection, world, np.asarray(chair.faces))
    return box, silhouette, projection


def test_the_committed_model_fits_a_chair_to_its_silhouette() -> None:
    box, mask, projection = _rendered_chair()
    assert mask.sum() > 2000
    generated = MeshGenerator(MODEL_DIR).generate("chair", box, mask, projection)
    assert generated is not None
    assert generated.iou > 0.6
    bounds = generated.mesh.bounds
    reach = np.linalg.norm(np.asarray(box.size)) / 2 * 1.3
    assert np.all(np.abs(bounds - np.asarray(box.center)) < reach)
    assert MeshGenerator(MODEL_DIR).generate("whiteboard", box, mask, projection) is None


def test_the_committed_model_records_its_training() -> None:
    metadata = json.loads((MODEL_DIR / "metadata.json").read_text())
    metrics = json.loads((MODEL_DIR / "metrics.json").read_text())
    assert metadata["classes"] == list(MESH_CLASSES)
    assert metrics["onnx_max_abs_difference"] < 1e-3
    assert metrics["cut_chamfer"] < metrics["template_chamfer"]
