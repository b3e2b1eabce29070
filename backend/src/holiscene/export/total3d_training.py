"""`holiscene export --format total3d-training`: stored scenes as the preprocessed training set
Total3DUnderstanding's training and testing code reads (Nie et al., CVPR 2020), so someone can
train or test Total3D on the scenes labelled here. DIR is laid out as Total3D's `data/sunrgbd/`:

- `sunrgbd_train_test_data/<n>.pkl`: one pickled dict per scene (photo, depth, camera, room
  layout and objects, every target already put into Total3D's bins, as its preprocessing
  writes them; the bins are those of Total3D's configs/data_config.py, restated below);
- `splits/train.json`, `splits/test.json`: the pickles' paths as Total3D opens them; a scene
  goes to test when the retraining here would hold it out (the same hash of its id);
- `preprocessed/size_avg_category.pkl` and `preprocessed/layout_avg_file.pkl`: the average
  object size per class and the average room, over the exported scenes (the priors its bins
  are residuals of; a class with no object gets the mean over all);
- `holiscene-index.json`: which scene and revision each <n> is, whether its labels are the
  ground truth it was imported with or the scene's own estimates, and what was left out.

A scene needs the camera's pitch and roll, a room layout and at least one object with a 2D
and a 3D box whose centre is in front of the camera: from its ground truth (gt.json) when it
was imported with one that has them, else from its current revision. Everything is in
Total3D's world frame, which is ours (export/total3d.py). Arrays are pickled so that NumPy 1
reads them too (as ndarray(shape, dtype, buffer), not NumPy 2's private module paths).
"""

from __future__ import annotations

import io
import json
import math
import pickle
from collections.abc import Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np
from holiscene_schema import NYU40_CLASSES, Scene, SceneObject
from PIL import Image

from ..core.atomic_files import write_atomic
from ..geometry.camera import PinholeCamera
from ..inputs.depth import depth_from_png
from ..segmentation.rle import decode_mask
from .archive import ArchivedScene, split_keys_of
from .errors import ExportRefusedError
from .total3d import box_frame

SAMPLES_DIR = "sunrgbd_train_test_data"
SPLITS_DIR = "splits"
PRIORS_DIR = "preprocessed"
INDEX_FILE = "holiscene-index.json"
# Where Total3D's code opens a pickle from (its working directory is its repository).
TOTAL3D_SAMPLE_PATH = "./data/sunrgbd/" + SAMPLES_DIR + "/{}.pkl"
PICKLE_PROTOCOL = 4  # Python 3.4 on, as Total3D's own preprocessing writes

# Total3D's bins (configs/data_config.py, Config.__initiate_bins), in radians and metres:
# [low, high] each, a value's class is the bin whose centre is nearest and its regression
# target its offset from that centre over the bin's width.
PITCH_BINS = [(math.radians(-60.0 + 40.0 * i), math.radians(-20.0 + 40.0 * i)) for i in range(2)]
ROLL_BINS = [(math.radians(-20.0 + 20.0 * i), math.radians(20.0 * i)) for i in range(2)]
LAYOUT_ORIENTATION_BINS = [(math.pi / 4 * (1 + i), math.pi / 4 * (2 + i)) for i in range(2)]
ORIENTATION_BINS = [(math.pi / 3 * (i - 3), math.pi / 3 * (i - 2)) for i in range(6)]
DISTANCE_BINS = [(float(i), float(i + 1)) for i in range(6)]

# Total3D's box corners: signs along the basis rows (net_utils/libs.py lists them so).
CORNER_SIGNS = np.array(
    [
        [-1, 1, -1],
        [-1, 1, 1],
        [1, 1, 1],
        [1, 1, -1],
        [-1, -1, -1],
        [-1, -1, 1],
        [1, -1, 1],
        [1, -1, -1],
    ],
    dtype=float,
)


def bin_class_and_offset(bins: Sequence[tuple[float, float]], value: float) -> tuple[int, float]:
    """The bin whose centre is nearest `value`, and value's offset from it over the width."""
    centres = [(low + high) / 2.0 for low, high in bins]
    index = int(np.argmin([abs(value - c) for c in centres]))
    width = bins[0][1] - bins[0][0]
    return index, (value - centres[index]) / width


def corners(basis: np.ndarray, coeffs: np.ndarray, centroid: np.ndarray) -> np.ndarray:
    """A box's 8 corners in Total3D's order."""
    return np.asarray(centroid + (CORNER_SIGNS * coeffs) @ basis)


def room_frame(corners_3d: list[list[float]]) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """The room as Total3D describes it: basis rows (the room's horizontal axis nearest the
    camera's forward, up, their cross product), half-sizes along them, and the centroid."""
    points = np.asarray(corners_3d, dtype=float)  # bottom 0-3 then the top 4-7 above them
    centroid = points.mean(axis=0)
    axes = [points[1] - points[0], points[3] - points[0]]
    lengths = [float(np.linalg.norm(a)) for a in axes]
    units = [a / n for a, n in zip(axes, lengths, strict=True)]
    frontal = max(range(2), key=lambda i: abs(units[i][0]))
    front = units[frontal] * (1.0 if units[frontal][0] >= 0 else -1.0)
    front = np.array([front[0], 0.0, front[2]]) / np.hypot(front[0], front[2])
    up = np.array([0.0, 1.0, 0.0])
    height = float(np.linalg.norm(points[4] - points[0]))
    coeffs = np.array([lengths[frontal], height, lengths[1 - frontal]]) / 2.0
    return np.stack([front, up, np.cross(front, up)]), coeffs, centroid


@dataclass(frozen=True)
class PlacedObject:
    obj: SceneObject
    label: int  # NYU-40 label: Total3D's class index
    basis: np.ndarray
    coeffs: np.ndarray
    centroid: np.ndarray


@dataclass(frozen=True)
class SceneGeometry:
    """What a scene gives Total3D before its binning, which needs the exported averages."""

    item: ArchivedScene
    scene: Scene
    source: str  # "ground truth" or "estimated"
    K: np.ndarray
    camera: PinholeCamera
    room: tuple[np.ndarray, np.ndarray, np.ndarray]
    objects: list[PlacedObject]
    left_out: list[str]  # object ids, each with why


def scene_geometry(item: ArchivedScene) -> SceneGeometry | str:
    """The scene's camera, room and placeable objects from its ground truth, or from its own
    estimates when it has none or the ground truth lacks them (NYU v2 measured no 3D boxes);
    else why it cannot be a sample."""
    if item.ground_truth is not None:
        truth = Scene.model_validate_json(item.ground_truth.read_bytes())
        measured = _geometry(item, truth, "ground truth")
        if not isinstance(measured, str):
            return measured
        estimated = _geometry(item, item.scene, f"estimated (its ground truth has {measured})")
        return estimated if not isinstance(estimated, str) else measured
    return _geometry(item, item.scene, "estimated")


def _geometry(item: ArchivedScene, scene: Scene, source: str) -> SceneGeometry | str:
    camera = scene.camera
    if camera is None or camera.pitch_deg is None or camera.roll_deg is None:
        return "no camera pitch and roll"
    if scene.layout.corners_3d is None:
        return "no room layout"
    K = np.asarray(camera.K, dtype=float)
    pinhole = PinholeCamera(K, camera.pitch_deg, camera.roll_deg)
    width, height = scene.image.width, scene.image.height
    placed, left_out = [], []
    for obj in scene.objects:
        if obj.box_3d is None:
            left_out.append(f"{obj.id}: no 3D box")
            continue
        basis, coeffs, centroid = box_frame(obj.box_3d)
        if np.isnan(pinhole.project(centroid)).any():
            left_out.append(f"{obj.id}: its centre is behind the camera")
            continue
        if _box_from_3d(corners(basis, coeffs, centroid), pinhole, width, height) is None:
            left_out.append(f"{obj.id}: its 3D box is out of the photo")
            continue
        label = NYU40_CLASSES.index(obj.cls) + 1
        placed.append(PlacedObject(obj, label, basis, coeffs, centroid))
    if not placed:
        return "no object with a 3D box in view"
    room = room_frame(scene.layout.corners_3d)
    return SceneGeometry(item, scene, source, K, pinhole, room, placed, left_out)


def _box_from_3d(
    box_corners: np.ndarray, camera: PinholeCamera, width: int, height: int
) -> list[float] | None:
    """The projected box's 2D bounds clipped to the photo, None when empty (Total3D's
    check_bdb)."""
    pixels = camera.project(box_corners)
    pixels = pixels[np.isfinite(pixels).all(axis=1)]  # the corners in front of the camera
    if not len(pixels):
        return None
    x1, y1 = max(float(pixels[:, 0].min()), 0.0), max(float(pixels[:, 1].min()), 0.0)
    x2, y2 = (
        min(float(pixels[:, 0].max()), width - 1.0),
        min(float(pixels[:, 1].max()), height - 1.0),
    )
    if x1 >= x2 or y1 >= y2 or x1 > width - 1 or y1 > height - 1:
        return None
    return [x1, y1, x2, y2]


@dataclass(frozen=True)
class Priors:
    """Total3D's preprocessed averages: half-sizes per class label (0-40) and the room's."""

    size_by_label: dict[int, np.ndarray]
    room_centroid: np.ndarray
    room_coeffs: np.ndarray


def averages(samples: Sequence[SceneGeometry]) -> Priors:
    sizes: dict[int, list[np.ndarray]] = {}
    for sample in samples:
        for placed in sample.objects:
            sizes.setdefault(placed.label, []).append(placed.coeffs)
    overall = np.mean([c for group in sizes.values() for c in group], axis=0)
    size_by_label = {
        label: np.mean(sizes[label], axis=0) if label in sizes else overall
        for label in range(len(NYU40_CLASSES) + 1)
    }
    rooms = [s.room for s in samples]
    return Priors(
        size_by_label,
        np.mean([centroid for _, _, centroid in rooms], axis=0),
        np.mean([coeffs for _, coeffs, _ in rooms], axis=0),
    )


def _mask_entry(placed: PlacedObject, width: int, height: int) -> dict[str, Any]:
    """Total3D's instance mask: the mask's own bounds and the mask cut to them (the 2D box
    filled when the object has no mask)."""
    obj = placed.obj
    if obj.mask is not None:
        full = decode_mask(obj.mask, width, height).astype(bool)
    else:
        full = np.zeros((height, width), bool)
        x1, y1, x2, y2 = (round(v) for v in obj.bbox)
        full[y1 : y2 + 1, x1 : x2 + 1] = True
    rows, cols = np.nonzero(full)
    if not len(rows):
        x1, y1, x2, y2 = (round(v) for v in obj.bbox)
        return {
            "msk_bdb": [x1, y1, x2, y2],
            "msk": np.ones((y2 - y1 + 1, x2 - x1 + 1), bool),
            "class_id": placed.label,
        }
    y1, y2, x1, x2 = int(rows.min()), int(rows.max()), int(cols.min()), int(cols.max())
    return {
        "msk_bdb": [x1, y1, x2, y2],
        "msk": full[y1 : y2 + 1, x1 : x2 + 1],
        "class_id": placed.label,
    }


def training_sample(geometry: SceneGeometry, priors: Priors, sequence_id: int) -> dict[str, Any]:
    """One pickle's dict, as Total3D's utils/generate_data.py (save_gt_result) lays it out."""
    scene, K, pinhole = geometry.scene, geometry.K, geometry.camera
    width, height = scene.image.width, scene.image.height
    # Total3D's pitch is positive looking up, ours looking down (docs/architecture.md).
    pitch, roll = math.radians(-pinhole.pitch_deg), math.radians(pinhole.roll_deg)
    pitch_cls, pitch_reg = bin_class_and_offset(PITCH_BINS, pitch)
    roll_cls, roll_reg = bin_class_and_offset(ROLL_BINS, roll)
    camera = {
        "pitch_cls": pitch_cls,
        "pitch_reg": pitch_reg,
        "roll_cls": roll_cls,
        "roll_reg": roll_reg,
        "K": K,
    }

    basis, coeffs, centroid = geometry.room
    front = basis[0]
    ori_cls, ori_reg = bin_class_and_offset(LAYOUT_ORIENTATION_BINS, math.atan2(front[0], front[2]))
    layout = {
        "ori_cls": ori_cls,
        "ori_reg": ori_reg,
        "centroid_reg": centroid - priors.room_centroid,
        "coeffs_reg": (coeffs - priors.room_coeffs) / priors.room_coeffs,
        "bdb3D": corners(basis, coeffs, centroid),
    }

    boxes: dict[str, list[Any]] = {}
    for placed in geometry.objects:
        box_corners = corners(placed.basis, placed.coeffs, placed.centroid)
        from_3d = _box_from_3d(box_corners, pinhole, width, height)
        assert from_3d is not None  # scene_geometry kept only objects in view
        x1, y1, x2, y2 = placed.obj.bbox
        u, v = pinhole.project(placed.centroid)[0]
        average = priors.size_by_label[placed.label]
        front = placed.basis[2]
        values = {
            "ori": bin_class_and_offset(ORIENTATION_BINS, math.atan2(front[0], front[2])),
            "centroid": bin_class_and_offset(DISTANCE_BINS, float(np.linalg.norm(placed.centroid))),
        }
        entry = {
            "ori_cls": values["ori"][0],
            "ori_reg": values["ori"][1],
            "size_reg": (placed.coeffs - average) / average,
            "bdb3D": box_corners,
            "bdb2D_from_3D": [
                from_3d[0] / K[0, 2],
                from_3d[1] / K[1, 2],
                from_3d[2] / K[0, 2],
                from_3d[3] / K[1, 2],
            ],
            "bdb2D_pos": [x1, y1, x2, y2],
            "centroid_cls": values["centroid"][0],
            "centroid_reg": values["centroid"][1],
            "delta_2D": [((x1 + x2) / 2.0 - u) / (x2 - x1), ((y1 + y2) / 2.0 - v) / (y2 - y1)],
            "size_cls": placed.label,
            "mask": _mask_entry(placed, width, height),
        }
        for key, value in entry.items():
            boxes.setdefault(key, []).append(value)
    masks = np.empty(len(geometry.objects), dtype=object)
    masks[:] = boxes.pop("mask")

    with Image.open(geometry.item.photo) as photo:
        rgb = np.asarray(photo.convert("RGB"))
    return {
        "rgb_img": rgb,
        "depth_map": _depth_metres(geometry.item, width, height),
        "boxes": {**{key: np.array(values) for key, values in boxes.items()}, "mask": masks},
        "camera": camera,
        "layout": layout,
        "sequence_id": sequence_id,
    }


def _depth_metres(item: ArchivedScene, width: int, height: int) -> np.ndarray:
    """The depth in metres (float32, 0 where there is none), zeros for a photo without."""
    if item.depth is None or not item.depth.is_file():
        return np.zeros((height, width), np.float32)
    return depth_from_png(item.depth.read_bytes(), width, height).metres.astype(np.float32)


class _PortablePickler(pickle.Pickler):
    """Writes arrays as ndarray(shape, dtype, buffer) and NumPy scalars as Python numbers, so
    NumPy 1 reads the files (NumPy 2's own pickles name its private numpy._core)."""

    def reducer_override(self, obj: Any) -> Any:
        if isinstance(obj, np.ndarray):
            if obj.dtype == object:
                return np.array, (obj.tolist(), "O")
            array = np.ascontiguousarray(obj)
            return np.ndarray, (array.shape, array.dtype.str, bytearray(array.tobytes()))
        if isinstance(obj, np.generic):
            return type(obj.item()), (obj.item(),)
        return NotImplemented


def portable_pickle(value: Any) -> bytes:
    buffer = io.BytesIO()
    _PortablePickler(buffer, protocol=PICKLE_PROTOCOL).dump(value)
    return buffer.getvalue()


def write_total3d_training(chosen: list[ArchivedScene], out: Path) -> str | None:
    """DIR as the module's description lays it out; ExportRefusedError (nothing written) when
    no scene can be a sample. Returns which scenes were left out and why."""
    from ..services.heldout import heldout_split  # the retraining's own split

    geometries: list[SceneGeometry] = []
    skipped: dict[str, str] = {}
    for item in chosen:
        made = scene_geometry(item)
        if isinstance(made, str):
            skipped[item.scene_id] = made
        else:
            geometries.append(made)
    if not geometries:
        reasons = "; ".join(f"{scene_id}: {why}" for scene_id, why in skipped.items())
        raise ExportRefusedError(f"no scene can be a Total3D training sample ({reasons})")
    priors = averages(geometries)
    items = [g.item for g in geometries]
    _, held_out = heldout_split([i.scene_id for i in items], split_keys_of(items))
    splits: dict[str, list[str]] = {"train": [], "test": []}
    index = []
    (out / SAMPLES_DIR).mkdir(exist_ok=True)
    for sequence_id, geometry in enumerate(geometries, start=1):
        sample = training_sample(geometry, priors, sequence_id)
        write_atomic(out / SAMPLES_DIR / f"{sequence_id}.pkl", portable_pickle(sample))
        split = "test" if geometry.item.scene_id in held_out else "train"
        splits[split].append(TOTAL3D_SAMPLE_PATH.format(sequence_id))
        index.append(
            {
                "sequence_id": sequence_id,
                "scene_id": geometry.item.scene_id,
                "name": geometry.scene.name,
                "revision": geometry.item.revision,
                "labels": geometry.source,
                "split": split,
                "objects": [p.obj.id for p in geometry.objects],
                "objects_left_out": geometry.left_out,
            }
        )
    (out / SPLITS_DIR).mkdir(exist_ok=True)
    for split, paths in splits.items():
        write_atomic(out / SPLITS_DIR / f"{split}.json", json.dumps(paths).encode())
    (out / PRIORS_DIR).mkdir(exist_ok=True)
    write_atomic(out / PRIORS_DIR / "size_avg_category.pkl", portable_pickle(priors.size_by_label))
    room_averages = {
        "layout_centroid_avg": priors.room_centroid.tolist(),
        "layout_coeffs_avg": priors.room_coeffs.tolist(),
    }
    write_atomic(out / PRIORS_DIR / "layout_avg_file.pkl", portable_pickle(room_averages))
    document = {"samples": index, "scenes_left_out": skipped}
    write_atomic(out / INDEX_FILE, (json.dumps(document, indent=1) + "\n").encode())
    counts = f"{len(splits['train'])} training and {len(splits['test'])} test sample(s)"
    if not skipped:
        return counts
    reasons = "; ".join(f"{scene_id}: {why}" for scene_id, why in skipped.items())
    return f"{counts}; {len(skipped)} scene(s) left out ({reasons})"
