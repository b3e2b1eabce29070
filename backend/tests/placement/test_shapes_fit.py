"""Model fitting: the model's turn in its box and its source, chosen by silhouette IoU; and
the scene's GLB with the fitted models and the room."""

from __future__ import annotations

import io
from pathlib import Path

import numpy as np
import pytest
import trimesh
from holiscene.geometry.camera import rot_y
from holiscene.pipeline.base import PipelineBuildError
from holiscene.pipeline.stages.mesh import SceneMesh
from holiscene.pipeline.stages.shapes_fit import ShapesFit
from holiscene.placement.oracle import context_from_truth
from holiscene.placement.projection import MaskTarget
from holiscene.placement.room import pinhole, projection_matrix, wrap_deg
from holiscene.placement.shape_choice import fit_model
from holiscene.segmentation.rle import decode_mask
from holiscene_schema import Box3D

from .scenes import SEEDS, placed, scene, visible_fraction

# Classes whose front can be told from their back by their silhouette.
FRONTED = {"chair", "sofa", "bed", "desk", "toilet", "television", "dresser", "night_stand"}


def _turned(box: Box3D, k: int) -> Box3D:
    d, h, w = box.size
    return Box3D(
        center=box.center,
        size=[d, h, w] if k % 2 == 0 else [w, h, d],
        yaw_deg=wrap_deg(box.yaw_deg + 90.0 * k),
    )


def test_the_front_is_found_from_the_true_box_turned_at_random() -> None:
    rng = np.random.default_rng(0)
    errors = []
    for seed in SEEDS:
        synthetic = scene(seed)
        truth = synthetic.truth
        assert truth.camera is not None
        camera = pinhole(truth.camera)
        assert camera is not None
        projection = projection_matrix(camera)
        for obj in truth.objects:
            if obj.cls not in FRONTED or visible_fraction(synthetic, obj) < 0.5:
                continue
            assert obj.box_3d is not None and obj.mask is not None
            mask = decode_mask(obj.mask, truth.image.width, truth.image.height)
            turned = _turned(obj.box_3d, int(rng.integers(1, 4)))
            fitted = fit_model(obj.cls, turned, MaskTarget(mask, max_side=96), projection, 1)
            errors.append(abs(wrap_deg(fitted.yaw_deg - obj.box_3d.yaw_deg)))
    assert len(errors) >= 5
    assert float(np.mean(np.array(errors) < 1.0)) >= 0.7, errors


def test_every_placed_object_gets_a_library_model_in_its_box() -> None:
    result = placed(3002)
    ctx = result.ctx
    ShapesFit().run(ctx)
    assert ctx.object_meshes is not None and ctx.boxes_3d is not None
    for obj_id, box in ctx.boxes_3d.items():
        assert box is not None
        fitted = ctx.object_meshes[obj_id]
        assert fitted.ref.library == "builtin" and fitted.ref.seed in (0, 1, 2)
        # In the box's own frame the model fills the box exactly (whichever way it faces).
        local = (np.asarray(fitted.mesh.vertices) - np.array(box.center)) @ rot_y(
            np.radians(box.yaw_deg)
        )
        assert local.min(axis=0) == pytest.approx(-np.array(box.size) / 2.0, abs=2e-3)
        assert local.max(axis=0) == pytest.approx(np.array(box.size) / 2.0, abs=2e-3)


def test_user_models_are_used_and_named(tmp_path: Path) -> None:
    folder = tmp_path / "models"
    for cls in ("table", "box"):
        (folder / cls).mkdir(parents=True)
        trimesh.creation.box(extents=(1.0, 0.5, 1.0)).export(folder / cls / "block.obj")
    ctx = context_from_truth(scene(3000))
    result = placed(3000)
    ctx.boxes_3d = dict(result.ctx.boxes_3d or {})
    ShapesFit(models_dir=str(folder), seeds=0).run(ctx)
    assert ctx.object_meshes is not None and ctx.objects is not None
    refs = {ctx.object_meshes[o.id].ref.library for o in ctx.objects if o.cls in ("table", "box")}
    assert refs == {"user"}
    assert {ctx.object_meshes[o.id].ref.file for o in ctx.objects if o.cls == "table"} == {
        "table/block.obj"
    }
    # Without a user model and without library variants, an object keeps its box.
    assert all(o.id not in ctx.object_meshes for o in ctx.objects if o.cls == "books")
    with pytest.raises(PipelineBuildError):
        ShapesFit(models_dir=str(tmp_path / "missing"))


def _glb_nodes(glb: bytes) -> set[str]:
    loaded = trimesh.load(io.BytesIO(glb), file_type="glb", force="scene")
    return set(loaded.graph.nodes_geometry)


def test_glb_holds_the_fitted_models_and_the_room() -> None:
    result = placed(3001)
    ctx = result.ctx
    ShapesFit().run(ctx)
    SceneMesh().run(ctx)
    assert ctx.scene_glb is not None and ctx.objects is not None
    nodes = _glb_nodes(ctx.scene_glb)
    expected = {o.id for o in ctx.objects} | {"floor", "ceiling"} | {f"wall_{i}" for i in range(4)}
    assert nodes == expected
    loaded = trimesh.load(io.BytesIO(ctx.scene_glb), file_type="glb", force="scene")
    assert ctx.object_meshes is not None
    first = ctx.objects[0].id
    assert len(loaded.geometry[first].faces) == len(ctx.object_meshes[first].mesh.faces)
    # Walls face the inside of the room.
    centre = np.array(result.synthetic.truth.layout.corners_3d).mean(axis=0)
    for i in range(4):
        wall = loaded.geometry[f"wall_{i}"]
        to_centre = centre - wall.vertices.mean(axis=0)
        assert float(wall.face_normals[0] @ to_centre) > 0


def test_glb_falls_back_to_boxes_and_stays_none_when_empty() -> None:
    ctx = placed(3001).ctx
    boxes_only = context_from_truth(scene(3001))
    boxes_only.boxes_3d = dict(ctx.boxes_3d or {})
    boxes_only.layout = None
    SceneMesh().run(boxes_only)
    assert boxes_only.scene_glb is not None and boxes_only.objects is not None
    assert _glb_nodes(boxes_only.scene_glb) == {o.id for o in boxes_only.objects} | {"floor"}
    empty = context_from_truth(scene(3001))
    empty.boxes_3d = {}
    empty.layout = None
    assert empty.camera is not None
    empty.camera = empty.camera.model_copy(update={"height_m": None})
    SceneMesh().run(empty)
    assert empty.scene_glb is None
