"""The viser scene of a synthetic room, read back from the running server's handles."""

from __future__ import annotations

import math
from collections.abc import Callable
from pathlib import Path

import numpy as np
import pytest
import viser.transforms as vtf
from holiscene.geometry.camera import PinholeCamera
from holiscene.shapes import SUPPORTED_CLASSES
from holiscene.viewer import SceneViewer, ViewerInput, load_scene_path
from holiscene.viewer.colours import object_colours
from holiscene.viewer.geometry import floor_height, object_corners
from holiscene.viewer.meshes import fills_box, glb_object_meshes
from holiscene.viewer.scene_viewer import (
    BEHIND_RGB,
    BELOW_RGB,
    COMPLETED_RGB,
    DIMMED_OPACITY,
    FRUSTUM_SCALE,
    PARTIAL_RGB,
    SEE_THROUGH_OPACITY,
)
from holiscene_schema import MeshRef

OpenViewer = Callable[[ViewerInput], SceneViewer]


def test_ground_truth_scene_has_every_node(synthetic_folder: Path, open_viewer: OpenViewer) -> None:
    data = load_scene_path(synthetic_folder / "gt.json")
    scene = data.scene
    assert data.photo is not None and data.photo.shape == (480, 640, 3)
    viewer = open_viewer(data)

    # One mesh per object, named by id, coloured as the page colours its mask, rebuilt from
    # its MeshRef and filling its box; furniture with a library model is more than a box.
    assert set(viewer.objects) == {o.id for o in scene.objects}
    colours = object_colours([o.id for o in scene.objects])
    assert len(set(colours.values())) == len(scene.objects)
    for obj in scene.objects:
        node = viewer.objects[obj.id]
        assert node.mesh.name == f"/objects/{obj.id}"
        assert tuple(node.mesh.color) == colours[obj.id]
        assert node.source == "library"
        corners = object_corners(obj)
        assert corners is not None
        assert fills_box(np.asarray(node.mesh.vertices), corners)
        if obj.cls in SUPPORTED_CLASSES and obj.cls not in ("box", "picture"):
            assert len(node.mesh.vertices) > 8, obj.cls

    # One arrow per support, supporter -> supported, red from below and blue from behind.
    assert set(viewer.arrows) == {s.child for s in scene.supports}
    assert {s.type for s in scene.supports} == {"below", "behind"}
    floor_y = floor_height(scene)
    assert floor_y is not None
    for support in scene.supports:
        arrow = viewer.arrows[support.child]
        assert arrow.name == f"/supports/{support.child}"
        start, end = np.asarray(arrow.points)[0]
        colour = BELOW_RGB if support.type == "below" else BEHIND_RGB
        assert tuple(np.asarray(arrow.colors).reshape(-1, 3)[0]) == colour
        corners = object_corners(next(o for o in scene.objects if o.id == support.child))
        assert corners is not None
        # The head sticks out of the supported object, away from the supporter.
        centre = corners.mean(axis=0)
        assert np.linalg.norm(end - start) > np.linalg.norm(centre - start)
        if support.parent == "floor":
            assert start[1] == pytest.approx(floor_y)
            assert end[1] > corners[:, 1].max()
        elif support.parent == "wall":
            assert abs(end[1] - start[1]) < 1e-6, "from the wall, horizontally"
        else:
            supporter = next(o for o in scene.objects if o.id == support.parent)
            supporter_corners = object_corners(supporter)
            assert supporter_corners is not None
            assert start == pytest.approx(supporter_corners.mean(axis=0))

    # The camera frustum: the photo on it, the photo's field of view, looking along the
    # camera's optical axis (pitch and roll of the scene).
    frustum = viewer.frustum
    assert frustum is not None and frustum.name == "/camera/photo"
    assert frustum.image is not None and frustum.image.shape == (480, 640, 3)
    assert scene.camera is not None and scene.camera.pitch_deg is not None
    K = np.asarray(scene.camera.K)
    assert frustum.fov == pytest.approx(2 * math.atan(240 / K[1, 1]))
    assert frustum.aspect == pytest.approx(640 / 480)
    assert frustum.scale == pytest.approx(FRUSTUM_SCALE)
    camera = PinholeCamera(K, scene.camera.pitch_deg, scene.camera.roll_deg or 0.0)
    looking = vtf.SO3(np.asarray(frustum.wxyz)).as_matrix()[:, 2]
    assert looking == pytest.approx(camera.optical_axis, abs=1e-6)
    assert np.asarray(frustum.position) == pytest.approx(0.0)

    assert set(viewer.room) == {"floor", "walls", "edges"}
    assert sorted(viewer.dropdown.options) == sorted(
        ["(none)"] + [f"{o.id} · {o.cls}" for o in scene.objects]
    )
    for obj in scene.objects:
        assert f"| {obj.id} | {obj.cls} |" in viewer.table.content


def test_selecting_an_object_highlights_it(synthetic_folder: Path, open_viewer: OpenViewer) -> None:
    data = load_scene_path(synthetic_folder / "gt.json")
    viewer = open_viewer(data)
    support = next(s for s in data.scene.supports if s.parent not in ("floor", "wall"))
    child = support.child

    # A reviewer picking it in the dropdown (server-side assignment runs the same callback).
    label = next(o for o in viewer.dropdown.options if o.startswith(f"{child} · "))
    viewer.dropdown.value = label
    assert viewer.selected == child
    for obj_id, node in viewer.objects.items():
        assert node.mesh.opacity == (None if obj_id == child else DIMMED_OPACITY)
    assert viewer.highlight is not None and viewer.highlight.name == "/highlight"
    assert np.asarray(viewer.highlight.points).shape == (12, 2, 3)
    details = viewer.details.content
    assert f"**{child}**" in details
    assert f"| supporter | {support.parent} (" in details
    assert f"| type | {support.type} |" in details
    assert "| confidence | 100% |" in details
    assert "| source | manual (synthetic) |" in details
    assert "| 3D box confidence | - |" in details  # ground truth: no model judged its box

    # Clicking another object in the scene does the same through `select`.
    other = next(o.id for o in data.scene.objects if o.id != child)
    viewer.select(other)
    assert viewer.dropdown.value.startswith(f"{other} · ")
    assert viewer.objects[child].mesh.opacity == DIMMED_OPACITY
    assert viewer.objects[other].mesh.opacity is None

    viewer.select(None)
    assert viewer.highlight is None
    assert all(node.mesh.opacity is None for node in viewer.objects.values())
    with pytest.raises(KeyError):
        viewer.select("no-such-object")


def test_prediction_takes_meshes_from_its_glb(
    synthetic_folder: Path, predicted_folder: Path, open_viewer: OpenViewer
) -> None:
    data = load_scene_path(predicted_folder, photo=synthetic_folder / "img.png")
    assert data.glb is not None and data.photo is not None
    scene = data.scene
    placed = {o.id for o in scene.objects if o.corners_3d is not None}
    unplaced = {o.id for o in scene.objects} - placed
    assert len(unplaced) == 1
    viewer = open_viewer(data)

    # Each placed object is its GLB node, vertex for vertex (turn included).
    assert set(viewer.objects) == placed
    from_glb = glb_object_meshes(data.glb)
    for obj_id, node in viewer.objects.items():
        assert node.source == "scene.glb"
        expected = np.asarray(from_glb[obj_id].vertices, dtype=np.float32)
        assert np.asarray(node.mesh.vertices) == pytest.approx(expected, abs=1e-5)

    # No arrow into or out of the object without a box; the panel says why.
    drawn = {s.child for s in scene.supports if s.child in placed and s.parent not in unplaced}
    assert set(viewer.arrows) == drawn
    assert drawn != {s.child for s in scene.supports}
    (missing,) = unplaced
    viewer.select(missing)
    assert "no 3D box" in viewer.details.content
    assert viewer.highlight is None


def test_details_name_the_stage_that_made_a_glb_mesh(
    synthetic_folder: Path, predicted_folder: Path, open_viewer: OpenViewer
) -> None:
    data = load_scene_path(predicted_folder, photo=synthetic_folder / "img.png")
    placed = [o for o in data.scene.objects if o.corners_3d is not None]
    made_by = {placed[0].id: "learned", placed[1].id: "completion"}
    objects = [
        o.model_copy(update={"mesh": MeshRef(library=made_by[o.id], cls=o.cls)})
        if o.id in made_by
        else o
        for o in data.scene.objects
    ]
    scene = data.scene.model_copy(update={"objects": objects})
    viewer = open_viewer(ViewerInput(scene, data.photo, data.glb, data.origin))
    expected = {
        "learned": "learned (the mesh network's template)",
        "completion": "from depth (shape completion)",
    }
    for obj_id, library in made_by.items():
        viewer.select(obj_id)
        assert f"| mesh | {expected[library]} (from scene.glb) |" in viewer.details.content
    # Without a MeshRef the GLB is all the viewer knows.
    viewer.select(placed[2].id)
    assert "| mesh | scene.glb |" in viewer.details.content


def test_glb_of_other_boxes_is_not_trusted(
    synthetic_folder: Path, predicted_folder: Path, open_viewer: OpenViewer
) -> None:
    """A GLB whose meshes fill other boxes (as after the objects moved) is not used for
    them: the objects' own models are rebuilt from their MeshRefs instead."""
    truth = load_scene_path(synthetic_folder / "gt.json").scene
    shift = np.array([0.3, 0.0, 0.0])
    moved = [
        o.model_copy(
            update={
                "box_3d": o.box_3d.model_copy(
                    update={"center": (np.array(o.box_3d.center) + shift).tolist()}
                ),
                "corners_3d": (np.array(o.corners_3d) + shift).tolist(),
            }
        )
        if o.box_3d is not None and o.corners_3d is not None and i % 2 == 0
        else o
        for i, o in enumerate(truth.objects)
    ]
    scene = truth.model_copy(update={"objects": moved})
    glb = (predicted_folder / "scene.glb").read_bytes()
    viewer = open_viewer(ViewerInput(scene, None, glb, "moved objects, older GLB"))
    placed_in_glb = set(glb_object_meshes(glb))
    for i, obj in enumerate(truth.objects):
        if obj.id not in placed_in_glb:
            assert viewer.objects[obj.id].source == "library"
        else:
            assert viewer.objects[obj.id].source == ("library" if i % 2 == 0 else "scene.glb")
    assert any("do not fill the boxes" in note for note in viewer.notes)
    assert viewer.frustum is not None and viewer.frustum.image is None


def test_scene_without_camera_or_layout(synthetic_folder: Path, open_viewer: OpenViewer) -> None:
    truth = load_scene_path(synthetic_folder / "gt.json").scene
    bare = truth.model_copy(update={"camera": None, "layout": type(truth.layout)()})
    viewer = open_viewer(ViewerInput(bare, None, None, "bare"))
    assert viewer.frustum is None and viewer.room == {}
    floor_children = {s.child for s in bare.supports if s.parent in ("floor", "wall")}
    # Without a room there is no floor to start from; walls fall back to behind the object.
    assert not {s.child for s in bare.supports if s.parent == "floor"} & set(viewer.arrows)
    assert {s.child for s in bare.supports if s.parent == "wall"} <= set(viewer.arrows)
    assert floor_children
    assert len(viewer.objects) == len(bare.objects)


def test_depth_points_are_drawn_when_asked(synthetic_folder: Path, open_viewer: OpenViewer) -> None:
    """The room came with depth.png: each object's partial points (orange) and completed
    points (teal) are point clouds, hidden until the reviewer ticks Depth points."""
    data = load_scene_path(synthetic_folder / "gt.json")
    assert data.depth is not None and data.depth.shape == (480, 640)
    viewer = open_viewer(data)
    partial = {n.rsplit("/", 1)[1] for n in viewer.depth_points if n.startswith("/depth/partial/")}
    completed = {
        n.rsplit("/", 1)[1] for n in viewer.depth_points if n.startswith("/depth/completed/")
    }
    assert len(partial) >= len(data.scene.objects) // 2 and completed and completed <= partial
    assert not viewer.depth_toggle.disabled and viewer.depth_toggle.value is False
    assert not any(cloud.visible for cloud in viewer.depth_points.values())
    viewer.depth_toggle.value = True
    assert all(cloud.visible for cloud in viewer.depth_points.values())
    # The meshes would hide the points on their surfaces: see-through while they are shown,
    # and a selection still dims the others more.
    assert all(node.mesh.opacity == SEE_THROUGH_OPACITY for node in viewer.objects.values())
    chosen = next(iter(viewer.objects))
    viewer.select(chosen)
    assert viewer.objects[chosen].mesh.opacity == SEE_THROUGH_OPACITY
    assert {n.mesh.opacity for i, n in viewer.objects.items() if i != chosen} == {DIMMED_OPACITY}
    viewer.select(None)
    corners = np.asarray(data.scene.layout.corners_3d)
    low, high = corners.min(axis=0) - 0.05, corners.max(axis=0) + 0.05
    for name, cloud in viewer.depth_points.items():
        points = np.asarray(cloud.points, dtype=float)
        assert len(points) > 0
        colour = PARTIAL_RGB if "/partial/" in name else COMPLETED_RGB
        assert tuple(np.asarray(cloud.colors).reshape(-1, 3)[0]) == colour
        if "/partial/" in name:  # seen surfaces: within the room's bounds
            assert ((points >= low) & (points <= high)).all(axis=1).mean() > 0.98, name
    viewer.depth_toggle.value = False
    assert not any(cloud.visible for cloud in viewer.depth_points.values())
    assert all(node.mesh.opacity is None for node in viewer.objects.values())


def test_without_depth_there_are_no_depth_points(
    synthetic_folder: Path, open_viewer: OpenViewer
) -> None:
    data = load_scene_path(synthetic_folder / "gt.json")
    viewer = open_viewer(
        ViewerInput(data.scene.model_copy(update={"depth": None}), None, None, "x")
    )
    assert viewer.depth_points == {} and viewer.depth_toggle.disabled
