"""How good the layout and object networks' estimates are on photos with true scenes
(validation during training, and the run-time tests): camera pitch and roll errors, the room's
3D IoU, and the share of true boxes whose estimate overlaps them at 3D IoU 0.15, the boxes
decoded with the LEN's own camera (the learned path alone)."""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import asdict, dataclass

import numpy as np

from ...evaluation.box_iou import iou_3d
from ...geometry.boxes import corners_of
from ...geometry.camera import PinholeCamera
from .outputs import object_estimates, room_estimate
from .samples import PhotoSample

FOUND_IOU = 0.15


@dataclass(frozen=True)
class ValidationScores:
    pitch_mae_deg: float
    roll_mae_deg: float
    layout_iou: float
    camera_height_error: float  # median relative error
    boxes_found: float
    distance_error: float  # median relative error of the box centres' distances

    def as_dict(self) -> dict[str, float]:
        return {k: round(float(v), 4) for k, v in asdict(self).items()}


def score_predictions(
    samples: Sequence[PhotoSample], rows: Sequence[tuple[np.ndarray, np.ndarray]]
) -> ValidationScores:
    pitch, roll, layout, height, found, distance = [], [], [], [], [], []
    for sample, (room_row, object_rows) in zip(samples, rows, strict=True):
        room = room_estimate(room_row)
        truth_height = float(np.exp(sample.log_height[0]))
        camera = PinholeCamera(sample.K.astype(float), room.pitch_deg, room.roll_deg)
        pitch.append(abs(room.pitch_deg - float(sample.pitch_roll[0])))
        roll.append(abs(room.roll_deg - float(sample.pitch_roll[1])))
        layout.append(iou_3d(room.corners_world(), sample.true_layout.astype(float)))
        height.append(abs(room.camera_height_m / truth_height - 1))
        for target, bbox, cls, corners in zip(
            object_estimates(object_rows),
            sample.bbox,
            sample.classes,
            sample.true_corners,
            strict=True,
        ):
            box = target.box(tuple(float(v) for v in bbox), str(cls), camera)
            found.append(iou_3d(corners_of(box), corners.astype(float)) >= FOUND_IOU)
            true_distance = float(np.linalg.norm(corners.mean(axis=0)))
            distance.append(abs(float(np.linalg.norm(box.center)) / true_distance - 1))
    return ValidationScores(
        pitch_mae_deg=float(np.mean(pitch)),
        roll_mae_deg=float(np.mean(roll)),
        layout_iou=float(np.mean(layout)),
        camera_height_error=float(np.median(height)),
        boxes_found=float(np.mean(found)) if found else 0.0,
        distance_error=float(np.median(distance)) if distance else 0.0,
    )
