"""What the box refiner reads: per object a vector of what the geometric pipeline found
(its class, support, 3D box against the class's typical size, 2D box, mask, camera, the scene's
overall size cue), and per pair of objects the geometry of their 2D boxes (the relation
module's input, as in Total3DUnderstanding). Shared by training and run time; no PyTorch.

And what it predicts per object (`TARGETS`): log ratios of the true box to the estimate, of
the centre's distance from the camera, the height, and the smaller and larger horizontal side.
"""

from __future__ import annotations

import math
from collections.abc import Mapping, Sequence
from dataclasses import dataclass

import numpy as np
from holiscene_schema import Box3D, Camera, SceneObject, SupportRelation
from numpy.typing import NDArray

from ...knowledge.object_sizes import middle_size
from ...shapes import SIZE_RANGES

SUPPORT_KINDS = ("floor", "below", "wall", "behind", "ceiling", "none")
PAIR_FEATURES = 4
TARGETS = ("distance", "height", "small side", "large side")
_EDGE = 2.0  # pixels: a 2D box this close to the photo's edge is cut by it


def typical_size(cls: str) -> NDArray[np.float64]:
    """The middle of the class's size range: (depth, height, width) in metres. A class the
    library has no sizes for reads 0.5 m each way, as the committed model was trained."""
    if cls not in SIZE_RANGES:
        return np.array([0.5, 0.5, 0.5])
    return np.array(middle_size(cls))


def _support_kind(relation: SupportRelation | None) -> str:
    if relation is None:
        return "none"
    if relation.parent in ("floor", "ceiling"):
        return relation.parent
    if relation.parent.startswith("wall"):
        return "wall"
    return "below" if relation.type == "below" else "behind"


def _log_size_ratios(size: Sequence[float], cls: str) -> list[float]:
    """log(height / typical), log(smaller horizontal side / typical smaller), log(larger ...)."""
    typical = typical_size(cls)
    estimate = [size[1], *sorted((size[0], size[2]))]
    prior = [typical[1], *sorted((typical[0], typical[2]))]
    return [math.log(max(e, 1e-3) / p) for e, p in zip(estimate, prior, strict=True)]


@dataclass(frozen=True)
class SceneView:
    """The parts of a reconstruction the refiner reads (from a Scene or a pipeline context)."""

    objects: Sequence[SceneObject]
    boxes: Mapping[str, Box3D | None]
    mask_pixels: Mapping[str, int]  # object id -> pixels of its mask
    supports: Sequence[SupportRelation]
    camera: Camera
    width: int
    height: int

    def placed(self) -> list[SceneObject]:
        return [o for o in self.objects if self.boxes.get(o.id) is not None]


def feature_names(classes: Sequence[str]) -> list[str]:
    return [
        *(f"class {c}" for c in classes),
        *(f"on {k}" for k in SUPPORT_KINDS),
        "log distance",
        "centre altitude / camera height",
        "centre elevation (sin)",
        "log height / typical",
        "log smaller side / typical",
        "log larger side / typical",
        "x1 / width",
        "y1 / height",
        "x2 / width",
        "y2 / height",
        "log box area / photo area",
        "cut on the left",
        "cut at the top",
        "cut on the right",
        "cut at the bottom",
        "mask pixels / box area",
        "box covered by a nearer object's box",
        "supporter's log height / typical",
        "camera pitch (rad)",
        "camera roll (rad)",
        "log camera height",
        "scene median log height / typical",
        "objects / 20",
    ]


def object_features(view: SceneView, classes: Sequence[str]) -> NDArray[np.float32]:
    """(objects with a 3D box, features) in the order of `view.placed()`."""
    placed = view.placed()
    if not placed:
        return np.zeros((0, len(feature_names(classes))), dtype=np.float32)
    if view.camera.height_m is None:
        raise ValueError("the box refiner needs the camera height")
    camera_height = float(view.camera.height_m)
    boxes = {o.id: view.boxes[o.id] for o in placed}
    by_id = {o.id: o for o in view.objects}
    support_of = {s.child: s for s in view.supports}
    distance = {i: float(np.linalg.norm(b.center)) for i, b in boxes.items() if b is not None}
    scene_size = (
        float(
            np.median([_log_size_ratios(boxes[o.id].size, o.cls)[0] for o in placed])  # type: ignore[union-attr]
        )
        if placed
        else 0.0
    )
    rows = []
    for obj in placed:
        box = boxes[obj.id]
        assert box is not None
        centre = np.asarray(box.center, dtype=float)
        x1, y1, x2, y2 = obj.bbox
        area = max((x2 - x1) * (y2 - y1), 1.0)
        covered = 0.0
        for other in placed:
            if other.id == obj.id or distance[other.id] >= distance[obj.id]:
                continue
            ox1, oy1, ox2, oy2 = other.bbox
            overlap = max(0.0, min(x2, ox2) - max(x1, ox1)) * max(0.0, min(y2, oy2) - max(y1, oy1))
            covered = max(covered, overlap / area)
        relation = support_of.get(obj.id)
        supporter_size = 0.0
        if relation is not None and relation.parent in boxes:
            supporter_box = boxes[relation.parent]
            assert supporter_box is not None
            supporter_size = _log_size_ratios(supporter_box.size, by_id[relation.parent].cls)[0]
        kind = _support_kind(relation)
        rows.append(
            [
                *(float(obj.cls == c) for c in classes),
                *(float(kind == k) for k in SUPPORT_KINDS),
                math.log(max(distance[obj.id], 1e-3)),
                (centre[1] + camera_height) / camera_height,
                centre[1] / max(distance[obj.id], 1e-3),
                *_log_size_ratios(box.size, obj.cls),
                x1 / view.width,
                y1 / view.height,
                x2 / view.width,
                y2 / view.height,
                math.log(area / (view.width * view.height)),
                float(x1 <= _EDGE),
                float(y1 <= _EDGE),
                float(x2 >= view.width - _EDGE),
                float(y2 >= view.height - _EDGE),
                view.mask_pixels.get(obj.id, 0) / area,
                covered,
                supporter_size,
                math.radians(view.camera.pitch_deg or 0.0),
                math.radians(view.camera.roll_deg or 0.0),
                math.log(camera_height),
                scene_size,
                len(placed) / 20.0,
            ]
        )
    return np.asarray(rows, dtype=np.float32).reshape(len(placed), -1)


def pair_features(objects: Sequence[SceneObject]) -> NDArray[np.float32]:
    """(n, n, 4): for object i and each j, j's 2D box centre offset in i's box widths and
    heights (signed log) and the log ratios of their widths and heights."""
    boxes = np.asarray([o.bbox for o in objects], dtype=np.float64).reshape(-1, 4)
    cx, cy = (boxes[:, 0] + boxes[:, 2]) / 2, (boxes[:, 1] + boxes[:, 3]) / 2
    w = np.maximum(boxes[:, 2] - boxes[:, 0], 1.0)
    h = np.maximum(boxes[:, 3] - boxes[:, 1], 1.0)
    dx = (cx[None, :] - cx[:, None]) / w[:, None]
    dy = (cy[None, :] - cy[:, None]) / h[:, None]
    pairs = np.stack(
        [
            np.sign(dx) * np.log1p(np.abs(dx)),
            np.sign(dy) * np.log1p(np.abs(dy)),
            np.log(w[None, :] / w[:, None]),
            np.log(h[None, :] / h[:, None]),
        ],
        axis=-1,
    )
    return pairs.astype(np.float32)


def targets(estimate: Box3D, truth: Box3D) -> NDArray[np.float32]:
    """log(true / estimated) of the distance, the height and the sorted horizontal sides."""
    distance = float(np.linalg.norm(truth.center)) / max(
        float(np.linalg.norm(estimate.center)), 1e-6
    )
    true_sides = sorted((truth.size[0], truth.size[2]))
    sides = sorted((estimate.size[0], estimate.size[2]))
    ratios: list[float] = [
        distance,
        truth.size[1] / estimate.size[1],
        true_sides[0] / sides[0],
        true_sides[1] / sides[1],
    ]
    return np.log(np.maximum(ratios, 1e-6)).astype(np.float32)


# How far the refiner may move or resize a box. A photo unlike the training rooms (a real
# photo's odd placement) can drive the network far outside what it learned. The distance's
# bound holds 97% of the training targets (and costs nothing on held-out rooms); sizes get
# more room, as a thin side (a picture's depth) may rightly grow several times.
MAX_LOG_DISTANCE = math.log(1.5)
MAX_LOG_SIZE = math.log(10.0)
MIN_SIDE = 0.01  # metres


def refined(box: Box3D, log_ratios: Sequence[float]) -> Box3D:
    """`box` moved along its ray and resized by predicted log ratios (`targets`' order),
    each held within the bounds above."""
    bounds = (MAX_LOG_DISTANCE, MAX_LOG_SIZE, MAX_LOG_SIZE, MAX_LOG_SIZE)
    distance, height, small, large = (
        math.exp(min(max(float(r), -bound), bound))
        for r, bound in zip(log_ratios, bounds, strict=True)
    )
    size = [float(v) for v in box.size]
    size[1] *= height
    small_axis, large_axis = (0, 2) if size[0] <= size[2] else (2, 0)
    size[small_axis] *= small
    size[large_axis] *= large
    centre = [float(v) * distance for v in box.center]
    return Box3D(
        center=[round(v, 4) for v in centre],
        size=[round(max(v, MIN_SIDE), 4) for v in size],
        yaw_deg=box.yaw_deg,
    )
