"""2D object detection scored against given boxes: recall whatever the class, recall with the
right class, precision, and mAP at an IoU threshold (VOC all-point, as the 3D boxes are).

Predictions are matched to truth one to one, best score first, each to the unmatched truth box
it overlaps most (at least `iou`), so a box counts once however many predictions sit on it.
"""

from __future__ import annotations

from collections import defaultdict
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from ..learning.detector.runtime import box_iou
from .metrics import all_point_average_precision

Box = tuple[float, float, float, float]
# mAP ranks every prediction down to this score (an operating threshold such as the pipeline's
# 0.3 would cut the precision-recall curve short); recall and precision are figures at the
# operating threshold.
MAP_SCORE_THRESHOLD = 0.05


@dataclass(frozen=True)
class ScoredBox:
    bbox: Box
    cls: str
    score: float = 1.0


def match(
    predicted: list[ScoredBox], truth: list[ScoredBox], iou: float, same_class: bool
) -> list[int | None]:
    """For each prediction (in the given order), the index of the truth box it matched."""
    taken = np.zeros(len(truth), dtype=bool)
    truth_boxes = np.array([t.bbox for t in truth], dtype=np.float64).reshape(-1, 4)
    result: list[int | None] = [None] * len(predicted)
    order = sorted(range(len(predicted)), key=lambda i: -predicted[i].score)
    for index in order:
        if not len(truth):
            break
        overlaps = box_iou(np.array(predicted[index].bbox, dtype=np.float64), truth_boxes)
        allowed = ~taken
        if same_class:
            allowed &= np.array([t.cls == predicted[index].cls for t in truth])
        overlaps = np.where(allowed, overlaps, -1.0)
        best = int(np.argmax(overlaps))
        if overlaps[best] >= iou:
            taken[best] = True
            result[index] = best
    return result


@dataclass
class DetectionEvaluation:
    iou: float = 0.5
    photos: int = 0
    truth_boxes: int = 0
    predicted_boxes: int = 0
    found_any_class: int = 0
    found_right_class: int = 0
    predictions_real: int = 0  # predictions that match some truth box, whatever its class
    truth_per_class: dict[str, int] = field(default_factory=lambda: defaultdict(int))
    # Truth boxes found per truth class: [whatever the predicted class, with the right class].
    found_per_class: dict[str, list[int]] = field(
        default_factory=lambda: defaultdict(lambda: [0, 0])
    )
    scored_hits: dict[str, list[tuple[float, bool]]] = field(
        default_factory=lambda: defaultdict(list)
    )

    def add(self, predicted: list[ScoredBox], truth: list[ScoredBox]) -> None:
        self.photos += 1
        self.truth_boxes += len(truth)
        self.predicted_boxes += len(predicted)
        any_class = match(predicted, truth, self.iou, same_class=False)
        right_class = match(predicted, truth, self.iou, same_class=True)
        self.found_any_class += sum(m is not None for m in any_class)
        self.found_right_class += sum(m is not None for m in right_class)
        self.predictions_real += sum(m is not None for m in any_class)
        for box in truth:
            self.truth_per_class[box.cls] += 1
        for column, matches in enumerate((any_class, right_class)):
            for matched in matches:
                if matched is not None:
                    self.found_per_class[truth[matched].cls][column] += 1
        for box, matched in zip(predicted, right_class, strict=True):
            self.scored_hits[box.cls].append((box.score, matched is not None))

    def average_precision(self, classes: set[str] | None = None) -> dict[str, float]:
        """AP per class with truth boxes (only `classes`, when given)."""
        return {
            cls: all_point_average_precision(self.scored_hits.get(cls, []), count)
            for cls, count in sorted(self.truth_per_class.items())
            if count > 0 and (classes is None or cls in classes)
        }

    def summary(self, classes: set[str] | None = None) -> dict[str, Any]:
        ap = self.average_precision(classes)
        return {
            "photos": self.photos,
            "truth_boxes": self.truth_boxes,
            "predicted_boxes": self.predicted_boxes,
            "recall_any_class": _share(self.found_any_class, self.truth_boxes),
            "recall_right_class": _share(self.found_right_class, self.truth_boxes),
            "precision": _share(self.predictions_real, self.predicted_boxes),
            "map": float(np.mean(list(ap.values()))) if ap else None,
            "ap": ap,
            "found_per_class": {
                cls: {
                    "truth": count,
                    "found": self.found_per_class[cls][0],
                    "right_class": self.found_per_class[cls][1],
                }
                for cls, count in sorted(self.truth_per_class.items())
            },
        }


def _share(part: int, whole: int) -> float | None:
    return part / whole if whole else None
