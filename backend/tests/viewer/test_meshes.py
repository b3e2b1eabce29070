"""The viewer's meshes when a scene has nothing better than its boxes."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import trimesh
from holiscene.viewer.geometry import object_corners
from holiscene.viewer.meshes import fills_box, object_meshes
from holiscene_schema import BOX_CORNER_SIGNS, Scene


def test_objects_without_a_mesh_are_shown_as_closed_boxes(synthetic_folder: Path) -> None:
    scene = Scene.model_validate_json((synthetic_folder / "gt.json").read_text())
    bare = scene.model_copy(
        update={"objects": [o.model_copy(update={"mesh": None}) for o in scene.objects]}
    )
    plan = object_meshes(bare, None)
    assert set(plan.meshes) == {o.id for o in bare.objects if object_corners(o) is not None}
    for obj in bare.objects:
        mesh = plan.meshes[obj.id]
        corners = object_corners(obj)
        assert corners is not None and mesh.source == "box"
        box = trimesh.Trimesh(mesh.vertices, mesh.faces, process=False)
        assert box.is_watertight and box.volume > 0  # outward faces
        assert np.isclose(box.volume, float(np.prod(obj.box_3d.size)), rtol=1e-3)  # type: ignore[union-attr]
        assert fills_box(mesh.vertices, corners)


def test_a_completed_mesh_may_stop_short_of_its_box_but_not_leave_it() -> None:
    signs = np.array(BOX_CORNER_SIGNS, dtype=float)
    corners = signs * 0.5 + np.array([2.0, 0.0, 1.0])  # a 1 m cube
    lower_half = corners.copy()
    lower_half[4:, 1] = 0.0
    assert fills_box(corners, corners)
    assert not fills_box(lower_half, corners)
    assert fills_box(lower_half, corners, inside_only=True)
    moved = corners + np.array([0.3, 0.0, 0.0])  # a GLB of another revision
    assert not fills_box(moved, corners, inside_only=True)
