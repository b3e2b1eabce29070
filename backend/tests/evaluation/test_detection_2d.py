"""2D detection scoring: one-to-one matching, and the truth boxes found per class."""

from __future__ import annotations

import pytest
from holiscene.evaluation.detection_2d import DetectionEvaluation, ScoredBox


def test_boxes_found_are_counted_per_truth_class() -> None:
    truth = [
        ScoredBox((0, 0, 10, 10), "pillow"),
        ScoredBox((20, 0, 30, 10), "pillow"),
        ScoredBox((0, 20, 40, 60), "bed"),
    ]
    predicted = [
        ScoredBox((0, 0, 10, 10), "pillow", 0.9),  # right class
        ScoredBox((20, 0, 30, 11), "books", 0.8),  # the box, the wrong class
        ScoredBox((1, 0, 10, 10), "pillow", 0.7),  # a second box on a pillow already found
        ScoredBox((100, 100, 120, 120), "bed", 0.6),  # nothing there
    ]
    evaluation = DetectionEvaluation(iou=0.5)
    evaluation.add(predicted, truth)
    summary = evaluation.summary()
    assert summary["found_per_class"] == {
        "bed": {"truth": 1, "found": 0, "right_class": 0},
        "pillow": {"truth": 2, "found": 2, "right_class": 1},
    }
    assert summary["recall_any_class"] == pytest.approx(2 / 3)
    assert summary["recall_right_class"] == pytest.approx(1 / 3)
    assert summary["precision"] == pytest.approx(2 / 4)


def test_counts_add_up_over_photos() -> None:
    evaluation = DetectionEvaluation(iou=0.5)
    for _ in range(3):
        evaluation.add(
            [ScoredBox((0, 0, 10, 10), "chair", 0.5)], [ScoredBox((0, 0, 10, 10), "chair")]
        )
    evaluation.add([], [ScoredBox((0, 0, 10, 10), "chair")])
    assert evaluation.summary()["found_per_class"]["chair"] == {
        "truth": 4,
        "found": 3,
        "right_class": 3,
    }
