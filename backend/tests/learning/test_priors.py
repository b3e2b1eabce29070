"""Support priors are counted correctly from a hand-made set of labelled scenes."""

from __future__ import annotations

import numpy as np
import pytest
from holiscene.learning.priors import SMOOTHING, SupportPriors, count_priors
from holiscene.learning.samples import NO_LABEL, SupportSample, answer_index


def _sample(classes: list[str], answers: list[tuple[int, str] | None]) -> SupportSample:
    n = len(classes)
    targets = [NO_LABEL if a is None else answer_index(a[0], a[1]) for a in answers]
    return SupportSample(
        "hand", {}, tuple(f"o{i}" for i in range(n)), tuple(classes), np.array(targets)
    )


# Columns: objects 0..n-1, then n = ceiling, n + 1 = floor, n + 2 = wall.
HAND_SET = [
    # lamp on the night stand, night stand on the floor, picture on the wall
    _sample(["lamp", "night_stand", "picture"], [(1, "below"), (4, "below"), (5, "behind")]),
    # lamp on the floor, table on the floor, one unlabelled box
    _sample(["lamp", "table", "box"], [(4, "below"), (4, "below"), None]),
    # lamp on the table
    _sample(["table", "lamp"], [(3, "below"), (0, "below")]),
]


def test_counts_match_the_hand_made_set() -> None:
    priors = count_priors(HAND_SET)
    assert priors.counts["lamp"] == {"night_stand|below": 1, "floor|below": 1, "table|below": 1}
    assert priors.counts["night_stand"] == {"floor|below": 1}
    assert priors.counts["table"] == {"floor|below": 2}
    assert priors.counts["picture"] == {"wall|behind": 1}
    assert "box" not in priors.counts  # unlabelled objects are not counted


def test_probabilities_are_smoothed_and_normalised() -> None:
    priors = count_priors(HAND_SET)
    # 6 labelled objects: floor|below 4, wall|behind 1, night_stand|below 1, table|below 1 ...
    background_floor = 4 / 7
    expected = (1 + SMOOTHING * background_floor) / (3 + SMOOTHING)
    assert priors.joint("floor", "lamp", "below") == pytest.approx(expected)
    total = sum(p for _, _, p in priors.ranked("lamp"))
    assert total == pytest.approx(1.0)
    assert priors.ranked("table")[0][:2] == ("floor", "below")
    below = [priors.conditional(p, "lamp", "below") for p in priors.supporter_classes("lamp")]
    assert sum(below) == pytest.approx(1.0)


def test_an_unseen_class_falls_back_to_what_all_classes_do() -> None:
    priors = count_priors(HAND_SET)
    assert priors.ranked("bathtub")[0][:2] == ("floor", "below")


def test_json_round_trip() -> None:
    priors = count_priors(HAND_SET)
    again = SupportPriors.from_json(priors.to_json())
    assert again.counts == priors.counts
    assert again.joint("table", "lamp", "below") == priors.joint("table", "lamp", "below")
