"""The Total3D training-set export: every binned target, decoded the way Total3D's own code
decodes them (net_utils/libs.py: bin centre + offset x width, boxes from the projected centre,
its distance and the orientation angle), gives back the true camera, room and boxes; the
pickles need nothing but NumPy's public names; scenes that cannot be samples are left out."""

from __future__ import annotations

import io
import json
import math
import pickle
from pathlib import Path
from typing import Any

import numpy as np
import pytest
from holiscene.export.archive import ArchivedScene
from holiscene.export.errors import ExportRefusedError
from holiscene.export.total3d_training import write_total3d_training
from holiscene.geometry.camera import PinholeCamera
from holiscene_schema import NYU40_CLASSES, Scene

from .test_total3d import TOTAL3D_CORNER_SIGNS

# Total3D's bins (configs/data_config.py), written out again here from its numbers.
DEG = math.pi / 180
PITCH_BINS = [[-60 * DEG, -20 * DEG], [-20 * DEG, 20 * DEG]]
ROLL_BINS = [[-20 * DEG, 0.0], [0.0, 20 * DEG]]
LAYOUT_ORI_BINS = [[math.pi / 4, math.pi / 2], [math.pi / 2, 3 * math.pi / 4]]
ORI_BINS = [[(i - 3) * math.pi / 3, (i - 2) * math.pi / 3] for i in range(6)]
DISTANCE_BINS = [[float(i), float(i + 1)] for i in range(6)]
SIGNS = np.array(TOTAL3D_CORNER_SIGNS)
PORTABLE_GLOBALS = {("numpy", "ndarray"), ("numpy", "array"), ("builtins", "bytearray")}


class NumpyOnlyUnpickler(pickle.Unpickler):
    """Refuses every global but the public NumPy names the export promises."""

    def find_class(self, module: str, name: str) -> Any:
        if (module, name) not in PORTABLE_GLOBALS:
            raise pickle.UnpicklingError(f"unexpected global {module}.{name}")
        return super().find_class(module, name)


def load(path: Path) -> Any:
    return NumpyOnlyUnpickler(io.BytesIO(path.read_bytes())).load()


def from_bins(bins: list[list[float]], index: int, offset: float) -> float:
    low, high = bins[index]
    return (low + high) / 2 + offset * (high - low)


def box_corners(basis: np.ndarray, coeffs: np.ndarray, centroid: np.ndarray) -> np.ndarray:
    return np.asarray(centroid + (SIGNS * coeffs) @ basis)


def sorted_rows(points: np.ndarray | list[list[float]]) -> np.ndarray:
    rounded = np.round(np.asarray(points, dtype=float), 4)
    return rounded[np.lexsort(rounded.T[::-1])]


def item(folder: Path, scene_id: str, truth_file: bool = True) -> ArchivedScene:
    scene = Scene.model_validate_json((folder / "gt.json").read_text())
    return ArchivedScene(
        scene_id, 3, scene, folder / "img.png", glb=None,
        ground_truth=folder / "gt.json" if truth_file else None,
        depth=folder / "depth.png",
    )  # fmt: skip


def test_total3ds_decoding_of_the_targets_gives_back_the_true_camera_room_and_boxes(
    synthetic_folder: Path, tmp_path: Path
) -> None:
    truth = Scene.model_validate_json((synthetic_folder / "gt.json").read_text())
    camera = truth.camera
    assert camera is not None and camera.pitch_deg is not None and camera.roll_deg is not None
    assert truth.layout.corners_3d is not None
    write_total3d_training([item(synthetic_folder, "0123456789ab")], tmp_path)

    sample = load(tmp_path / "sunrgbd_train_test_data" / "1.pkl")
    sizes = load(tmp_path / "preprocessed" / "size_avg_category.pkl")
    room_avg = load(tmp_path / "preprocessed" / "layout_avg_file.pkl")
    assert sample["sequence_id"] == 1
    assert sample["rgb_img"].shape == (truth.image.height, truth.image.width, 3)
    assert sample["rgb_img"].dtype == np.uint8 and sample["depth_map"].dtype == np.float32
    assert 0.3 < float(np.median(sample["depth_map"])) < 15  # metres, from depth.png

    cam = sample["camera"]
    pitch = from_bins(PITCH_BINS, cam["pitch_cls"], cam["pitch_reg"])
    roll = from_bins(ROLL_BINS, cam["roll_cls"], cam["roll_reg"])
    # Total3D's pitch is positive looking up; ours is positive looking down.
    assert pitch == pytest.approx(-math.radians(camera.pitch_deg), abs=1e-9)
    assert roll == pytest.approx(math.radians(camera.roll_deg), abs=1e-9)
    assert np.allclose(cam["K"], camera.K)

    layout = sample["layout"]
    # Each angle lies in its bin (a room axis turned the other way would decode the same
    # corners from outside the bins Total3D's network classifies into).
    regressions = [
        cam["pitch_reg"],
        cam["roll_reg"],
        layout["ori_reg"],
        *sample["boxes"]["ori_reg"],
    ]
    assert all(abs(r) <= 0.5 + 1e-9 for r in regressions)
    ori = from_bins(LAYOUT_ORI_BINS, layout["ori_cls"], layout["ori_reg"])
    basis = np.array(
        [[math.sin(ori), 0, math.cos(ori)], [0, 1, 0], [-math.cos(ori), 0, math.sin(ori)]]
    )
    centroid = layout["centroid_reg"] + np.array(room_avg["layout_centroid_avg"])
    coeffs = (layout["coeffs_reg"] + 1) * np.array(room_avg["layout_coeffs_avg"])
    room = box_corners(basis, coeffs, centroid)
    assert np.allclose(sorted_rows(room), sorted_rows(truth.layout.corners_3d), atol=2e-4)
    assert np.allclose(layout["bdb3D"], room, atol=1e-6)

    boxes = sample["boxes"]
    placed = [o for o in truth.objects if o.box_3d is not None]
    assert list(boxes["size_cls"]) == [NYU40_CLASSES.index(o.cls) + 1 for o in placed]
    pinhole = PinholeCamera(np.asarray(camera.K), camera.pitch_deg, camera.roll_deg)
    for i, obj in enumerate(placed):
        x1, y1, x2, y2 = boxes["bdb2D_pos"][i]
        assert [x1, y1, x2, y2] == obj.bbox
        dx, dy = boxes["delta_2D"][i]
        centre_px = np.array([[(x1 + x2) / 2 - (x2 - x1) * dx, (y1 + y2) / 2 - (y2 - y1) * dy]])
        distance = from_bins(DISTANCE_BINS, boxes["centroid_cls"][i], boxes["centroid_reg"][i])
        ray = pinhole.ray(centre_px)[0]
        centroid = ray / np.linalg.norm(ray) * distance
        ori = from_bins(ORI_BINS, boxes["ori_cls"][i], boxes["ori_reg"][i])
        basis = np.array(
            [[math.cos(ori), 0, -math.sin(ori)], [0, 1, 0], [math.sin(ori), 0, math.cos(ori)]]
        )
        coeffs = (boxes["size_reg"][i] + 1) * sizes[int(boxes["size_cls"][i])]
        decoded = box_corners(basis, coeffs, centroid)
        # Total3D lists corners top face first; that is ours in reverse order.
        assert np.allclose(decoded, np.asarray(obj.corners_3d)[::-1], atol=1e-4), obj.id
        assert np.allclose(boxes["bdb3D"][i], decoded, atol=1e-6)
        mask = boxes["mask"][i]
        mx1, my1, mx2, my2 = mask["msk_bdb"]
        assert mask["msk"].shape == (my2 - my1 + 1, mx2 - mx1 + 1) and mask["msk"].dtype == bool
        assert mask["msk"].any() and mask["class_id"] == boxes["size_cls"][i]


def test_scenes_without_a_camera_or_room_are_left_out_and_named_and_the_split_is_the_holdouts(
    synthetic_folder: Path, tmp_path: Path
) -> None:
    no_room = item(synthetic_folder, "00000000000b", truth_file=False)
    no_room.scene.layout.corners_3d = None
    no_camera = item(synthetic_folder, "00000000000c", truth_file=False)
    no_camera.scene.camera = None
    chosen = [item(synthetic_folder, f"00000000000{n}") for n in range(4)]
    note = write_total3d_training([*chosen, no_room, no_camera], tmp_path)

    assert note is not None and "00000000000b: no room layout" in note
    assert "00000000000c: no camera pitch and roll" in note
    index = json.loads((tmp_path / "holiscene-index.json").read_text())
    assert index["scenes_left_out"] == {
        "00000000000b": "no room layout",
        "00000000000c": "no camera pitch and roll",
    }
    assert [s["scene_id"] for s in index["samples"]] == [c.scene_id for c in chosen]
    assert all(s["labels"] == "ground truth" for s in index["samples"])
    train = json.loads((tmp_path / "splits" / "train.json").read_text())
    test = json.loads((tmp_path / "splits" / "test.json").read_text())
    assert train and test and len(train) + len(test) == 4
    for entry in index["samples"]:
        path = f"./data/sunrgbd/sunrgbd_train_test_data/{entry['sequence_id']}.pkl"
        assert path in (test if entry["split"] == "test" else train)
        assert (tmp_path / "sunrgbd_train_test_data" / f"{entry['sequence_id']}.pkl").is_file()


def test_nothing_is_written_when_no_scene_can_be_a_sample(
    synthetic_folder: Path, tmp_path: Path
) -> None:
    lone = item(synthetic_folder, "00000000000d", truth_file=False)
    lone.scene.camera = None
    with pytest.raises(ExportRefusedError, match="no camera pitch and roll"):
        write_total3d_training([lone], tmp_path)
    assert list(tmp_path.iterdir()) == []


def test_a_ground_truth_without_3d_boxes_gives_way_to_the_scenes_own_estimates(
    synthetic_folder: Path, tmp_path: Path
) -> None:
    """NYU v2's ground truth has supports and masks but no 3D boxes or room."""
    truth = Scene.model_validate_json((synthetic_folder / "gt.json").read_text())
    flat = truth.model_copy(deep=True)
    for obj in flat.objects:
        obj.box_3d = obj.corners_3d = None
    (tmp_path / "gt.json").write_text(flat.model_dump_json())
    nyu_like = ArchivedScene(
        "00000000000e", 2, truth, synthetic_folder / "img.png", None, tmp_path / "gt.json"
    )
    out = tmp_path / "out"
    out.mkdir()
    write_total3d_training([nyu_like], out)
    index = json.loads((out / "holiscene-index.json").read_text())
    (sample,) = index["samples"]
    assert sample["labels"] == "estimated (its ground truth has no object with a 3D box in view)"
