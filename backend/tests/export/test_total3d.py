"""The Total3DUnderstanding export: MAT-files as the format says, and the camera, room and
boxes in Total3D's terms, checked against numbers worked out by hand from both conventions
(docs/architecture.md, "Conventions")."""

from __future__ import annotations

import json
import math
import struct
from pathlib import Path

import numpy as np
import pytest
from holiscene.export.archive import ArchivedScene
from holiscene.export.matfile import MatCell, MatStruct, mat_file
from holiscene.export.total3d import (
    box_struct,
    camera_rotation,
    layout_corners,
    total3d_class,
    write_total3d_scene,
)
from holiscene.geometry.boxes import box_corners
from holiscene.geometry.camera import PinholeCamera
from holiscene.viewer.meshes import object_meshes
from holiscene_schema import NYU40_CLASSES, Box3D, Camera, Scene
from PIL import Image

from .mat_reader import read_mat

# Total3D's corner signs along its basis rows (net_utils/libs.py get_corners_of_bb3d).
TOTAL3D_CORNER_SIGNS = [
    (-1, 1, -1), (-1, 1, 1), (1, 1, 1), (1, 1, -1),
    (-1, -1, -1), (-1, -1, 1), (1, -1, 1), (1, -1, -1),
]  # fmt: skip


def total3d_corners(basis: np.ndarray, coeffs: np.ndarray, centroid: np.ndarray) -> np.ndarray:
    return np.array(
        [centroid + sum(s * c * row for s, c, row in zip(signs, coeffs, basis, strict=True))
         for signs in TOTAL3D_CORNER_SIGNS]
    )  # fmt: skip


def test_a_matrix_is_laid_out_as_the_format_says() -> None:
    data = mat_file({"a": np.array([[1.0, 2.0]])}, description="a test")
    header = b"MATLAB 5.0 MAT-file, written by a test".ljust(116, b" ") + bytes(8)
    assert data[:128] == header + b"\x00\x01IM"
    flags = struct.pack("<IIII", 6, 8, 6, 0)  # miUINT32, 8 bytes: mxDOUBLE_CLASS, nzmax
    dims = struct.pack("<IIii", 5, 8, 1, 2)  # miINT32: 1 x 2
    name = struct.pack("<II", 1, 1) + b"a" + bytes(7)  # miINT8, padded to 8 bytes
    values = struct.pack("<II2d", 9, 16, 1.0, 2.0)  # miDOUBLE, column-major
    body = flags + dims + name + values
    assert data[128:] == struct.pack("<II", 14, len(body)) + body  # one miMATRIX


def test_structs_cells_and_int64_read_back() -> None:
    entry = MatStruct({"basis": np.eye(3) * 2, "classid": np.array(5, dtype=np.int64)})
    data = mat_file({"bdb": MatCell([entry, entry]), "ids": np.array([5, 7], dtype=np.int64)})
    read = read_mat(data)
    assert len(read["bdb"]) == 2
    assert np.array_equal(read["bdb"][1]["basis"], np.eye(3) * 2)
    assert read["bdb"][0]["classid"].tolist() == [[5]]
    assert read["ids"].tolist() == [[5, 7]]  # a 1-D array is a row
    with pytest.raises(TypeError, match="float64 and int64"):
        mat_file({"a": np.array([1], dtype=np.int32)})


def test_a_box_becomes_basis_coeffs_and_centroid_by_hand() -> None:
    # Yaw 90: the front (local x) turns from +x to -z, the right (local z) to +x.
    box = Box3D(center=[3.0, 0.5, -1.0], size=[2.0, 1.0, 0.5], yaw_deg=90.0)
    entry = box_struct(box, "chair").fields
    # Rows (-right, up, front); half-sizes along them (right, up, front).
    expected_basis = [[-1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, -1.0]]
    assert np.allclose(np.asarray(entry["basis"]), expected_basis, atol=1e-12)
    assert np.asarray(entry["coeffs"]).tolist() == [0.25, 0.5, 1.0]
    assert np.asarray(entry["centroid"]).tolist() == [3.0, 0.5, -1.0]
    assert np.asarray(entry["classid"]).item() == 5  # chair is NYU-40 label 5
    # Total3D's basis_from_ori(ori) at ori = yaw + 90 degrees gives the same rows.
    ori = math.radians(90.0 + 90.0)
    by_angle = np.array(
        [[math.cos(ori), 0, -math.sin(ori)], [0, 1, 0], [math.sin(ori), 0, math.cos(ori)]]
    )
    assert np.allclose(np.asarray(entry["basis"]), by_angle, atol=1e-12)


@pytest.mark.parametrize("yaw", [0.0, 30.0, 90.0, -135.0])
def test_total3d_corners_of_a_box_are_ours_in_reverse_order(yaw: float) -> None:
    box = Box3D(center=[3.0, -0.4, 0.7], size=[1.2, 0.8, 0.6], yaw_deg=yaw)
    fields = box_struct(box, "table").fields
    theirs = total3d_corners(
        np.asarray(fields["basis"]), np.asarray(fields["coeffs"]), np.asarray(fields["centroid"])
    )
    ours = box_corners(np.array(box.center), np.array(box.size), box.yaw_deg)
    assert np.allclose(theirs, ours[::-1], atol=1e-9)


def test_the_room_corners_follow_total3d_order_with_the_room_axes_as_basis() -> None:
    center, size, yaw = np.array([2.5, 0.2, 0.3]), np.array([6.0, 2.8, 4.0]), 15.0
    ours = box_corners(center, size, yaw)
    a = math.radians(yaw)
    basis = np.array([[math.cos(a), 0, -math.sin(a)], [0, 1, 0], [math.sin(a), 0, math.cos(a)]])
    expected = total3d_corners(basis, size / 2, center)
    assert np.allclose(layout_corners(ours.tolist()), expected, atol=1e-9)


def test_cam_r_is_world_from_forward_up_right_with_total3d_pitch_up() -> None:
    camera = Camera(K=np.eye(3).tolist(), K_source="given", pitch_deg=30.0, roll_deg=0.0)
    c, s = math.cos(math.radians(30)), math.sin(math.radians(30))
    # Looking 30 degrees down: the optical axis (forward) goes to (cos, -sin, 0).
    assert np.allclose(camera_rotation(camera), np.array([[c, s, 0], [-s, c, 0], [0, 0, 1]]))
    tilted = Camera(K=np.eye(3).tolist(), K_source="given", pitch_deg=12.0, roll_deg=-4.0)
    # Our rotation from OpenCV's frame is cam_R after OpenCV -> (forward, up, right).
    cv_to_fur = np.array([[0.0, 0, 1], [0, -1, 0], [1, 0, 0]])
    pinhole = PinholeCamera(np.eye(3), 12.0, -4.0)
    assert np.allclose(camera_rotation(tilted) @ cv_to_fur, pinhole.world_from_cv)


def test_class_names_are_total3d_spelling() -> None:
    assert total3d_class("refrigerator") == "refridgerator"
    assert total3d_class("night_stand") == "night_stand"


def test_a_scene_folder_holds_total3d_input_results_and_our_labels(
    synthetic_folder: Path, tmp_path: Path
) -> None:
    truth = Scene.model_validate_json((synthetic_folder / "gt.json").read_text())
    truth.objects[2].box_3d = None  # an object not placed: its entry is NaN, the order kept
    folder = tmp_path / "room"
    item = ArchivedScene("0123456789ab", 1, truth, synthetic_folder / "img.png", glb=None)
    write_total3d_scene(item, folder)
    camera = truth.camera
    assert camera is not None and truth.layout.corners_3d is not None

    with Image.open(folder / "img.jpg") as image:
        assert image.format == "JPEG" and image.size == (truth.image.width, truth.image.height)
    assert np.allclose(np.loadtxt(folder / "cam_K.txt"), camera.K, atol=1e-5)
    detections = json.loads((folder / "detections.json").read_text())
    assert [d["class"] for d in detections] == [total3d_class(o.cls) for o in truth.objects]
    for item, obj in zip(detections, truth.objects, strict=True):
        assert item["bbox"] == obj.bbox
        assert obj.mask is not None and "source" not in item["mask"]
        assert item["mask"] == obj.mask.model_dump(mode="json", exclude={"source"})

    cam_r = read_mat((folder / "r_ex.mat").read_bytes())["cam_R"]
    assert cam_r.tolist() == camera_rotation(camera).tolist()
    layout = read_mat((folder / "layout.mat").read_bytes())["layout"]
    assert np.allclose(layout, layout_corners(truth.layout.corners_3d))
    boxes = read_mat((folder / "bdb_3d.mat").read_bytes())
    assert len(boxes["bdb"]) == len(truth.objects)
    for entry, obj, label in zip(boxes["bdb"], truth.objects, boxes["class_id"][0], strict=True):
        assert entry["classid"].item() == label == NYU40_CLASSES.index(obj.cls) + 1
        if obj.box_3d is None:
            assert np.isnan(entry["centroid"]).all()
            continue
        corners = total3d_corners(entry["basis"], entry["coeffs"][0], entry["centroid"][0])
        assert np.allclose(corners, np.asarray(obj.corners_3d)[::-1], atol=2e-3), obj.id


def total3d_placed_mesh(
    obj_text: str, basis: np.ndarray, coeffs: np.ndarray, centroid: np.ndarray
) -> np.ndarray:
    """An exported .obj's vertices placed as Total3D's viewer places them
    (utils/visualize.py format_mesh): bounds centred, stretched to the coeffs, turned by the
    basis, moved to the centroid."""
    points = np.array(
        [
            [float(v) for v in line.split()[1:4]]
            for line in obj_text.splitlines()
            if line.startswith("v ")
        ]
    )
    points = points - (points.max(0) + points.min(0)) / 2.0
    points = points / ((points.max(0) - points.min(0)) / 2.0) * coeffs
    return np.asarray(points @ basis + centroid)


def test_object_meshes_are_written_in_their_box_frame_as_total3d_places_them(
    synthetic_folder: Path, tmp_path: Path
) -> None:
    truth = Scene.model_validate_json((synthetic_folder / "gt.json").read_text())
    truth.objects[2].box_3d = None  # not placed: no mesh, the other files keep their index
    folder = tmp_path / "room"
    item = ArchivedScene("0123456789ab", 1, truth, synthetic_folder / "img.png", glb=None)
    write_total3d_scene(item, folder)

    placed_ids = [(i, o) for i, o in enumerate(truth.objects) if o.box_3d is not None]
    expected = {f"{i}_{NYU40_CLASSES.index(o.cls) + 1}.obj" for i, o in placed_ids}
    assert {p.name for p in folder.glob("*.obj")} == expected
    world = object_meshes(truth, None).meshes
    boxes = read_mat((folder / "bdb_3d.mat").read_bytes())["bdb"]
    for index, obj in placed_ids:
        entry = boxes[index]
        text = (folder / f"{index}_{NYU40_CLASSES.index(obj.cls) + 1}.obj").read_text()
        placed = total3d_placed_mesh(text, entry["basis"], entry["coeffs"][0], entry["centroid"][0])
        assert world[obj.id].source == "library"
        assert len(placed) == len(world[obj.id].vertices)
        assert np.allclose(placed, world[obj.id].vertices, atol=2e-3), obj.id
