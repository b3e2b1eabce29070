"""How sure the box refiner is of a box it refined: the chance that the box overlaps the true
one at 3D IoU FOUND_IOU or more (`SceneObject.box_3d_confidence`).

It reads what the ensemble says of its own doubt (each target's expected error and how far the
members disagree) and the refined box itself: a small box far away must be placed more exactly
than a large near one to overlap its true box as much. A logistic regression over these,
fitted on the validation rooms after training (numpy only: fitted at training, applied at run
time, its weights in the model's metadata). 3D detectors from one photo rank their boxes the
same way, by a learned 3D confidence.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

import numpy as np
from holiscene_schema import Box3D
from numpy.typing import NDArray

from ...evaluation.metrics import AP_IOU
from .features import TARGETS

FOUND_IOU = AP_IOU  # a true box is found by a box with 3D IoU >= 0.15, as `holiscene eval` counts
# Below this chance a refined box is more likely wrong than right (the stage's note; the
# object list's orange badge, frontend/src/editors/boxConfidence.ts, uses the same half).
DOUBTFUL_CHANCE = 0.5

CONFIDENCE_FEATURES: tuple[str, ...] = (
    *(f"log expected error of the {t}" for t in TARGETS),
    *(f"log spread of the members' {t}" for t in TARGETS),
    "log smaller side / distance",
    "log larger side / distance",
    "log distance",
)
_FLOOR = 1e-6  # under the logs: a spread of 0 (one member) stays finite


def confidence_features(
    box: Box3D, log_scales: NDArray[np.float32], spreads: NDArray[np.float32]
) -> NDArray[np.float64]:
    """CONFIDENCE_FEATURES of one refined box, from its ensemble output row's parts."""
    distance = max(float(np.linalg.norm(box.center)), 1e-3)
    sides = sorted(float(v) for v in box.size)
    return np.array(
        [
            *(float(v) for v in log_scales),
            *(math.log(float(v) + _FLOOR) for v in spreads),
            math.log(sides[0] / distance),
            math.log(sides[-1] / distance),
            math.log(distance),
        ]
    )


@dataclass(frozen=True)
class ConfidenceModel:
    """Logistic regression on standardised CONFIDENCE_FEATURES: weights[0] is the intercept."""

    mean: NDArray[np.float64]
    std: NDArray[np.float64]
    weights: NDArray[np.float64]

    def chance(self, features: NDArray[np.float64]) -> NDArray[np.float64]:
        """(boxes, features) -> (boxes,) chances in (0, 1)."""
        z = (features - self.mean) / self.std
        logits = self.weights[0] + z @ self.weights[1:]
        chances: NDArray[np.float64] = 1.0 / (1.0 + np.exp(-logits))
        return chances

    def to_json(self) -> dict[str, Any]:
        return {
            "features": list(CONFIDENCE_FEATURES),
            "mean": [round(float(v), 6) for v in self.mean],
            "std": [round(float(v), 6) for v in self.std],
            "weights": [round(float(v), 6) for v in self.weights],
        }

    @classmethod
    def from_json(cls, data: dict[str, Any]) -> ConfidenceModel:
        if list(data["features"]) != list(CONFIDENCE_FEATURES):
            raise ValueError("the model's confidence reads other features than this code makes")
        return cls(
            mean=np.asarray(data["mean"], dtype=float),
            std=np.asarray(data["std"], dtype=float),
            weights=np.asarray(data["weights"], dtype=float),
        )


def fit_confidence(
    features: NDArray[np.float64], found: NDArray[np.bool_], l2: float = 1.0
) -> ConfidenceModel:
    """Logistic regression of `found` on `features` by Newton's method, with an L2 penalty
    (not on the intercept) that keeps the weights finite when the few validation boxes
    separate."""
    if len(features) == 0:
        raise ValueError("no validation box to fit the confidence on")
    mean = features.mean(0)
    std = np.where(features.std(0) < 1e-9, 1.0, features.std(0))
    design = np.c_[np.ones(len(features)), (features - mean) / std]
    target = found.astype(float)
    penalty = l2 * np.eye(design.shape[1])
    penalty[0, 0] = 0.0
    weights = np.zeros(design.shape[1])
    for _ in range(50):
        p = 1.0 / (1.0 + np.exp(-design @ weights))
        gradient = design.T @ (p - target) + penalty @ weights
        hessian = (
            (design * (p * (1 - p))[:, None]).T @ design + penalty + 1e-9 * np.eye(len(weights))
        )
        step = np.linalg.solve(hessian, gradient)
        weights -= step
        if np.abs(step).max() < 1e-8:
            break
    return ConfidenceModel(mean=mean, std=std, weights=weights)
