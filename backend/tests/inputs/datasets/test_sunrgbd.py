"""SUN RGB-D image folders: a synthetic room written in SUN's layout and frames comes back as
the generator made it (camera, 3D boxes, room, outlines), the 3D boxes project onto their
outlines, 3D boxes join 2D objects by index and name, the depth is read with its bits turned
back (depth/ before depth_bfx/), and bad folders fail one by one."""

from __future__ import annotations

import json
import shutil
from pathlib import Path

import cv2
import numpy as np
import pytest
from holiscene.geometry.camera import PinholeCamera
from holiscene.inputs.datasets import dataset_items, is_dataset
from holiscene.segmentation.rle import decode_mask
from holiscene_schema import Scene

from .files import HEIGHT, WIDTH, photo_bytes, write_json
from .sunrgbd_files import read_depth_mm, write_sun_depth, write_sun_folder

SEED = 5  # a bedroom of 16 labelled objects
HEADINGS = (0.0, 23.0, -140.0)  # the SUN gravity frame's turn from the camera's heading


@pytest.fixture(scope="module")
def synth_dir(tmp_path_factory: pytest.TempPathFactory) -> Path:
    from holiscene.synth.generate import synthesize_to

    return synthesize_to(SEED, tmp_path_factory.mktemp("synth"))


def _import_one(folder: Path) -> Scene:
    (item,) = dataset_items(folder)
    assert item.error is None and item.inputs is not None
    assert item.inputs.ground_truth is not None
    return item.inputs.ground_truth


def _yaw_gap(a: float, b: float) -> float:
    return abs((a - b + 180.0) % 360.0 - 180.0)


@pytest.mark.parametrize("heading", HEADINGS)
def test_the_ground_truth_comes_back_as_generated(
    synth_dir: Path, tmp_path: Path, heading: float
) -> None:
    truth = write_sun_folder(synth_dir, tmp_path / "NYU0005", heading)
    found = _import_one(tmp_path / "NYU0005")
    assert found.camera is not None and truth.camera is not None
    assert np.allclose(found.camera.K, truth.camera.K)
    assert abs((found.camera.pitch_deg or 0) - (truth.camera.pitch_deg or 0)) < 1e-3
    assert abs((found.camera.roll_deg or 0) - (truth.camera.roll_deg or 0)) < 1e-3
    assert abs((found.camera.height_m or 0) - (truth.camera.height_m or 0)) < 1e-3
    assert found.layout.source == "ground_truth"
    assert np.allclose(found.layout.corners_3d or [], truth.layout.corners_3d or [], atol=1e-3)
    for a, b in zip(found.layout.corners_2d or [], truth.layout.corners_2d or [], strict=True):
        assert (a is None) == (b is None)
        assert a is None or b is None or np.allclose(a, b, atol=0.1)
    assert [o.id for o in found.objects] == [o.id for o in truth.objects]
    assert [o.cls for o in found.objects] == [o.cls for o in truth.objects]
    for obj, expected in zip(found.objects, truth.objects, strict=True):
        assert obj.box_3d is not None and expected.box_3d is not None
        assert np.allclose(obj.box_3d.center, expected.box_3d.center, atol=1e-3), obj.id
        assert np.allclose(obj.box_3d.size, expected.box_3d.size, atol=1e-3), obj.id
        assert _yaw_gap(obj.box_3d.yaw_deg, expected.box_3d.yaw_deg) < 1e-2, obj.id
        assert np.allclose(obj.corners_3d or [], expected.corners_3d or [], atol=1e-3)


def test_3d_boxes_listed_in_another_order_find_their_objects_by_name_and_overlap(
    synth_dir: Path, tmp_path: Path
) -> None:
    """If a folder's 3D file does not share the 2D file's object order (no public code relies
    on it), each box still joins the object of its name its projection fits, even where the
    index holds another object of the same name (this room has five boxes and three
    pictures)."""
    truth = write_sun_folder(synth_dir, tmp_path / "NYU0005")
    path = tmp_path / "NYU0005" / "annotation3Dfinal" / "index.json"
    boxes = json.loads(path.read_text())
    boxes["objects"] = boxes["objects"][1:] + boxes["objects"][:1]  # every index moved by one
    write_json(path, boxes)
    found = _import_one(tmp_path / "NYU0005")
    names = [o.cls for o in truth.objects]
    assert any(names[i] == names[i + 1] for i in range(len(names) - 1))
    for obj, expected in zip(found.objects, truth.objects, strict=True):
        assert obj.box_3d is not None and expected.box_3d is not None, obj.id
        assert np.allclose(obj.box_3d.center, expected.box_3d.center, atol=1e-3), obj.id


def test_the_outlines_become_the_objects(synth_dir: Path, tmp_path: Path) -> None:
    truth = write_sun_folder(synth_dir, tmp_path / "NYU0005")
    (item,) = dataset_items(tmp_path / "NYU0005")
    assert item.inputs is not None and item.inputs.K is not None
    assert np.allclose(item.inputs.K, truth.camera.K if truth.camera else [])
    detections = item.inputs.detections or []
    assert [d.cls for d in detections] == [o.cls for o in truth.objects]
    width, height = truth.image.width, truth.image.height
    whole = 0
    for detection, expected in zip(detections, truth.objects, strict=True):
        assert detection.mask is not None and expected.mask is not None
        assert detection.mask.source == "given"
        mine = decode_mask(detection.mask, width, height)
        theirs = decode_mask(expected.mask, width, height)
        assert (mine & ~theirs).sum() <= 0.03 * mine.sum(), expected.id  # nothing beside it
        if cv2.connectedComponents(theirs.astype(np.uint8))[0] == 2:  # one part, outlined
            whole += 1
            assert detection.bbox == tuple(expected.bbox)
            assert (mine & theirs).sum() / (mine | theirs).sum() > 0.97
    assert whole >= len(detections) // 2


@pytest.mark.parametrize("heading", HEADINGS)
def test_the_3d_boxes_project_onto_their_outlines(
    synth_dir: Path, tmp_path: Path, heading: float
) -> None:
    """Independent of the generator's numbers: seen through the imported camera, each 3D box
    covers its object's 2D outline, and mostly no more (a wrong frame lands elsewhere)."""
    write_sun_folder(synth_dir, tmp_path / "NYU0005", heading)
    found = _import_one(tmp_path / "NYU0005")
    assert found.camera is not None
    camera = PinholeCamera(
        np.array(found.camera.K), found.camera.pitch_deg or 0.0, found.camera.roll_deg or 0.0
    )
    size = np.array([found.image.width, found.image.height])
    overlaps = []
    for obj in found.objects:
        corners = camera.project(np.array(obj.corners_3d))
        assert not np.isnan(corners).any()
        x1, y1 = np.clip(corners.min(axis=0), 0, size)
        x2, y2 = np.clip(corners.max(axis=0), 0, size)
        bx1, by1, bx2, by2 = obj.bbox
        assert bx1 >= x1 - 2 and by1 >= y1 - 2 and bx2 <= x2 + 2 and by2 <= y2 + 2, obj.id
        inter = max(0.0, min(bx2, x2) - max(bx1, x1)) * max(0.0, min(by2, y2) - max(by1, y1))
        overlaps.append(inter / ((bx2 - bx1) * (by2 - by1) + (x2 - x1) * (y2 - y1) - inter))
    assert np.median(overlaps) > 0.8


# A small hand-written folder: a 96x64 photo, two outlines, a level camera.
def _small_folder(folder: Path) -> Path:
    (folder / "image").mkdir(parents=True)
    (folder / "image" / "0000001.jpg").write_bytes(photo_bytes(3, kind="JPEG"))
    (folder / "depth").mkdir()
    (folder / "intrinsics.txt").write_text("80 0 48\n0 80 32\n0 0 1\n")
    (folder / "extrinsics").mkdir()
    (folder / "extrinsics" / "1.txt").write_text("1 0 0 0\n0 1 0 0\n0 0 1 0\n")
    write_json(
        folder / "annotation2Dfinal" / "index.json",
        {
            "frames": [
                {
                    "polygon": [
                        {"x": [10, 30, 30, 10], "y": [10, 10, 40, 40], "object": 0},
                        {"x": [50, 80, 80], "y": [20, 20, 50], "object": 2},
                    ]
                }
            ],
            "objects": [{"name": "chair"}, None, {"name": "sofa"}],
        },
    )
    return folder


def test_3d_boxes_join_2d_objects_by_index_and_name(tmp_path: Path) -> None:
    folder = _small_folder(tmp_path / "a")
    # Where the chair's outline is: left of the optical axis, taller than the photo.
    box = {"X": [-1.2, -0.6, -0.6, -1.2], "Z": [2.0, 2.0, 2.6, 2.6], "Ymin": -0.8, "Ymax": 1.0}
    annotation = json.loads((folder / "annotation2Dfinal" / "index.json").read_text())
    annotation["frames"][0]["polygon"] += [
        {"x": [5, 9, 9], "y": [50, 50, 60], "object": 0},  # a second part of the chair
        {"x": [80, 90, 90], "y": [50, 50, 60], "object": 0},  # another chair, outside its box
        {"x": [1, 2, 2], "y": [1, 1, 2], "object": 7},  # no such object: left out
    ]
    annotation["objects"] += [{"name": "Teapot3"}, {"name": "wall"}]  # a wall is the room
    annotation["frames"][0]["polygon"] += [
        {"x": [60, 70, 70], "y": [5, 5, 15], "object": 3},
        {"x": [0, 95, 95, 0], "y": [0, 0, 9, 9], "object": 4},
    ]
    write_json(folder / "annotation2Dfinal" / "index.json", annotation)
    write_json(
        folder / "annotation3Dfinal" / "index.json",
        {
            "objects": [
                {"name": "chair", "polygon": [box]},
                None,
                {"name": "table", "polygon": [box]},  # another name at sofa's index
            ]
        },
    )
    room = {"X": [-2, 2, 2.5, 0, -2], "Z": [0, 0, 4, 5, 4], "Ymin": -1.2, "Ymax": 1.4}
    write_json(folder / "annotation3Dlayout" / "index.json", {"objects": [{"polygon": room}]})
    (item,) = dataset_items(folder)
    assert item.inputs is not None and item.inputs.ground_truth is not None
    # Each outline is an object, as SUN's public readers take them, but for a piece inside
    # the 3D box of another outline of its entry: that is one object cut in two.
    chair, other_chair, sofa, teapot = item.inputs.detections or []
    assert (chair.cls, other_chair.cls, sofa.cls, teapot.cls) == (
        "chair",
        "chair",
        "sofa",
        "otherprop",
    )
    assert teapot.source_class == "teapot" and not teapot.class_known
    assert chair.bbox == (5.0, 10.0, 31.0, 61.0)  # the outline (10, 10, 31, 41) and its piece
    assert chair.mask is not None and chair.mask.source == "given"
    pieces = decode_mask(chair.mask, 96, 64)
    assert pieces[20, 20] and pieces[52, 8] and not pieces[45, 20]  # two parts, not their hull
    assert other_chair.bbox == (80.0, 50.0, 91.0, 61.0)
    assert item.inputs.notes == (
        "annotation2Dfinal/index.json object 0 (chair): 2 outlines inside its one 3D box "
        "joined as one object",
    )
    truth = item.inputs.ground_truth
    assert [o.id for o in truth.objects] == ["o0", "o1", "o2", "o3"]
    box_3d = truth.objects[0].box_3d  # the outline the box fits best
    assert box_3d is not None and truth.objects[1].box_3d is None
    assert truth.objects[0].mask == chair.mask.model_copy(update={"source": "ground_truth"})
    assert truth.objects[2].box_3d is None  # the table's box names no sofa
    # Level camera, gravity frame along the camera: SUN's Z is forward, X right, Y down.
    assert np.allclose(box_3d.center, [2.3, -0.1, -0.9]) and np.allclose(
        box_3d.size, [0.6, 1.8, 0.6]
    )
    assert _yaw_gap(box_3d.yaw_deg, 180.0) < 1e-9  # its first two corners are the near side
    assert truth.layout.corners_3d is None and "5 corners" in (truth.layout.note or "")
    assert truth.camera is not None and truth.camera.pitch_deg == 0.0
    assert truth.camera.height_m == 1.4  # the room's floor, though the room is no box


def test_image_folders_are_found_at_any_depth(tmp_path: Path) -> None:
    root = tmp_path / "SUNRGBD"
    _small_folder(root / "kv1" / "NYUdata" / "NYU0002")
    _small_folder(root / "kv1" / "NYUdata" / "NYU0001")
    plain = _small_folder(root / "realsense" / "lg" / "2014_10_24-14_37_53-1311000073")
    shutil.rmtree(plain / "annotation2Dfinal")
    write_json(root / "class_map.json", {"sofa": "bed"})  # the user's names, for every folder
    assert is_dataset(root) and is_dataset(root / "kv1" / "NYUdata" / "NYU0001")
    items = list(dataset_items(root))
    assert [Path(i.name).name for i in items] == [
        "NYU0001",
        "NYU0002",
        "2014_10_24-14_37_53-1311000073",
    ]
    assert all(i.inputs is not None for i in items)
    assert items[0].inputs is not None
    assert [d.cls for d in items[0].inputs.detections or []] == ["chair", "bed"]
    assert items[2].inputs is not None and items[2].inputs.detections is None


def test_a_bad_folder_is_its_own_error_and_the_rest_are_read(tmp_path: Path) -> None:
    root = tmp_path / "SUNRGBD"
    _small_folder(root / "a_good")
    (_small_folder(root / "b_not_json") / "annotation2Dfinal" / "index.json").write_text("{x")
    two = _small_folder(root / "c_two_points")
    annotation = json.loads((two / "annotation2Dfinal" / "index.json").read_text())
    annotation["frames"][0]["polygon"][1] = {"x": [50, 80], "y": [20, 20], "object": 2}
    write_json(two / "annotation2Dfinal" / "index.json", annotation)
    shutil.rmtree(_small_folder(root / "d_no_image") / "image")
    (_small_folder(root / "e_eight_numbers") / "intrinsics.txt").write_text("80 0 48 0 80 32 0 0")
    (_small_folder(root / "f_bad_tilt") / "extrinsics" / "2.txt").write_text("1 2 3\n")
    # The toolbox reads only the rotation: a file of the 3x3 alone is fine.
    (_small_folder(root / "h_rotation_only") / "extrinsics" / "1.txt").write_text(
        "1 0 0\n0 1 0\n0 0 1\n"
    )
    flat = {"X": [0, 1], "Z": [1, 2], "Ymin": 0, "Ymax": 1}
    write_json(
        _small_folder(root / "g_bad_box") / "annotation3Dfinal" / "index.json",
        {"objects": [{"name": "chair", "polygon": [flat]}]},
    )
    items = list(dataset_items(root))
    assert [Path(i.name).name for i in items] == [
        "a_good",
        "b_not_json",
        "c_two_points",
        "d_no_image",
        "e_eight_numbers",
        "f_bad_tilt",
        "g_bad_box",
        "h_rotation_only",
    ]
    good, not_json, two_points, *broken, rotation_only = items
    assert good.inputs is not None and good.error is None and good.inputs.notes == ()
    assert rotation_only.inputs is not None and rotation_only.inputs.ground_truth is not None
    # An outline of 2 points leaves out that outline (here the sofa's only one), not the photo.
    assert two_points.inputs is not None and two_points.error is None
    assert [d.cls for d in two_points.inputs.detections or []] == ["chair"]
    assert two_points.inputs.notes == ("polygon 1 of object 2 (sofa) has 2 point(s): left out",)
    assert all(i.inputs is None for i in [not_json, *broken])
    errors = [i.error or "" for i in [not_json, *broken]]
    assert "index.json is not valid JSON" in errors[0]
    assert "image/ holds no .jpg image" in errors[1]
    assert "intrinsics.txt must hold 9 numbers" in errors[2] and "it holds 8" in errors[2]
    assert "extrinsics/2.txt: must hold 3 rows of 4 numbers" in errors[3]
    assert "annotation3Dfinal/index.json object 0: a box's floor polygon has 4 corners" in errors[4]


def test_holiscene_import_stores_the_ground_truth_beside_the_scene(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    from holiscene.cli import main
    from holiscene.cli.export import scene_store
    from holiscene.core.settings import Settings

    root = tmp_path / "SUNRGBD"
    _small_folder(root / "kv1" / "NYU0001")
    (_small_folder(root / "kv1" / "NYU0002") / "intrinsics.txt").write_text("80 0 48 0 80 32")
    data_dir = tmp_path / "data"
    assert main(["import", str(root), "--data-dir", str(data_dir)]) == 1
    assert "NYU0002: intrinsics.txt must hold 9 numbers (the 3x3 intrinsics), it holds 6" in (
        capsys.readouterr().err
    )
    with scene_store(Settings(data_dir=data_dir)) as scenes:
        (summary,) = scenes.list_summaries()
        stored = scenes.document(summary.id).scene
        truth_file = scenes.files.ground_truth_path(summary.id)
    assert stored.name == "NYU0001" and [o.cls for o in stored.objects][:2] == ["chair", "sofa"]
    truth = Scene.model_validate_json(truth_file.read_text())
    assert truth.camera is not None and truth.camera.pitch_deg == 0.0
    assert [o.id for o in truth.objects] == ["o0", "o1"]
    assert main(["import", str(root / "kv1" / "NYU0001"), "--data-dir", str(data_dir)]) == 0
    assert "imported before" in capsys.readouterr().out


def test_the_depth_comes_back_in_metres(synth_dir: Path, tmp_path: Path) -> None:
    write_sun_folder(synth_dir, tmp_path / "NYU0005")
    (item,) = dataset_items(tmp_path / "NYU0005")
    assert item.inputs is not None and item.inputs.depth is not None
    true_mm = read_depth_mm(synth_dir)
    assert np.allclose(item.inputs.depth.metres, true_mm * 0.001, atol=1e-6)


def test_depth_bfx_is_read_only_without_depth(tmp_path: Path) -> None:
    folder = _small_folder(tmp_path / "a")
    (folder / "depth_bfx").mkdir()
    write_sun_depth(folder / "depth_bfx" / "0000001.png", np.full((HEIGHT, WIDTH), 1500))
    write_sun_depth(folder / "depth" / "0000000.png", np.full((HEIGHT, WIDTH), 900))
    write_sun_depth(folder / "depth" / "0000001.png", np.full((HEIGHT, WIDTH), 2000))

    def depth_m() -> float:
        (item,) = dataset_items(folder)
        assert item.inputs is not None and item.inputs.depth is not None, item.error
        return float(item.inputs.depth.metres[0, 0])

    assert depth_m() == pytest.approx(2.0)  # depth/, the file named as the photo
    (folder / "depth" / "0000001.png").unlink()
    assert depth_m() == pytest.approx(0.9)  # depth/'s first by name
    shutil.rmtree(folder / "depth")
    assert depth_m() == pytest.approx(1.5)


def test_a_folder_with_bad_depth_is_its_own_error(tmp_path: Path) -> None:
    root = tmp_path / "SUNRGBD"
    _small_folder(root / "a_good")
    eight = _small_folder(root / "b_eight_bit") / "depth" / "0000001.png"
    assert cv2.imwrite(str(eight), np.full((HEIGHT, WIDTH), 200, np.uint8))
    for name, millimetres in (("c_small", np.ones((8, 8))), ("d_zeros", np.zeros((HEIGHT, WIDTH)))):
        write_sun_depth(_small_folder(root / name) / "depth" / "0000001.png", millimetres)
    items = list(dataset_items(root))
    assert items[0].inputs is not None and items[0].inputs.depth is None
    assert all(i.inputs is None for i in items[1:])
    errors = [i.error or "" for i in items[1:]]
    assert "depth/0000001.png is an 8-bit image" in errors[0]
    assert f"depth/0000001.png is 8x8 pixels, the photo is {WIDTH}x{HEIGHT}" in errors[1]
    assert "depth/0000001.png holds no depth" in errors[2]
