"""Shape scores in the true box's frame and in the mesh's own box: a true mesh put in a box
that is moved, scaled and turned a quarter scores badly where the true box is and as itself
in its own box."""

from __future__ import annotations

import math

import numpy as np
import trimesh
from holiscene.evaluation.shape_eval import ShapeEvaluation
from holiscene.geometry.camera import rot_y
from holiscene.shapes import generate_shape
from holiscene_schema import Box3D, MeshRef, SceneObject


def _chair(box: Box3D, seed: int) -> tuple[SceneObject, trimesh.Trimesh]:
    obj = SceneObject(
        id="o0",
        cls="chair",
        bbox=[0.0, 0.0, 10.0, 10.0],
        box_3d=box,
        mesh=MeshRef(library="builtin", cls="chair", seed=seed),
    )
    mesh = generate_shape("chair", tuple(box.size), np.random.default_rng(seed)).mesh
    transform = np.eye(4)
    transform[:3, :3] = rot_y(math.radians(box.yaw_deg))
    transform[:3, 3] = box.center
    return obj, mesh.copy().apply_transform(transform)


def test_own_box_leaves_out_the_placement_and_the_turn() -> None:
    true_box = Box3D(center=[3.0, -0.9, 0.5], size=[0.55, 0.9, 0.5], yaw_deg=20.0)
    truth, itself = _chair(true_box, seed=4)
    # The same chair scaled twice as big, 0.6 m away, in a box turned a quarter (depth and
    # width swapped, so the chair's front is along the box's width).
    moved = Box3D(center=[3.6, -0.9, 0.2], size=[1.0, 1.8, 1.1], yaw_deg=110.0)
    mesh = itself.copy()
    mesh.apply_translation(-np.asarray(true_box.center))
    mesh.apply_scale(2.0)
    mesh.apply_translation(moved.center)
    evaluation = ShapeEvaluation()
    evaluation._add_object("room/o0", truth, "builtin", mesh, None, moved)
    evaluation._add_object("room/itself", truth, "builtin", itself, None, true_box)
    row = evaluation.records["room/o0"]
    noise = evaluation.records["room/itself"]["builtin"]["chamfer"]  # two samplings of one mesh
    assert row["builtin"]["chamfer"] > 10 * noise
    assert row["builtin, own box"]["chamfer"] < 1.3 * noise
    same_normals = evaluation.records["room/itself"]["builtin"]["normal_consistency"]
    assert row["builtin, own box"]["normal_consistency"] > same_normals - 0.03


def test_a_wrong_shape_in_its_own_box_scores_worse_than_the_right_one() -> None:
    box = Box3D(center=[2.0, -0.7, 0.0], size=[0.55, 0.9, 0.5], yaw_deg=0.0)
    truth, right = _chair(box, seed=4)
    table = generate_shape("table", tuple(box.size), np.random.default_rng(4)).mesh
    table.apply_translation(box.center)
    evaluation = ShapeEvaluation()
    evaluation._add_object("room/right", truth, "builtin", right, None, box)
    evaluation._add_object("room/wrong", truth, "builtin", table, None, box)
    own = "builtin, own box"
    right_score = evaluation.records["room/right"][own]["chamfer"]
    wrong_score = evaluation.records["room/wrong"][own]["chamfer"]
    assert wrong_score > 2 * right_score
