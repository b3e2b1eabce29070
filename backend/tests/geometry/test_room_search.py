"""The room search's coordinate ascent: grid rounds, then finer steps off the grid."""

from __future__ import annotations

import math

import numpy as np
import pytest
from holiscene.geometry import room_layout
from holiscene.geometry.room_layout import RoomHypothesis, coordinate_search

TARGET = {"front": 3.37, "left": 1.23, "right": 2.61, "ceiling": 0.87}
GRIDS = {
    "front": np.geomspace(0.8, 14.0, 28),
    "left": np.geomspace(0.2, 8.0, 24),
    "right": np.geomspace(0.2, 8.0, 24),
    "ceiling": np.geomspace(0.5, 2.5, 20),
}
START = RoomHypothesis(
    front=5.0, left=2.0, right=2.0, back=0.5, ceiling=1.0, score=0.0, ceiling_seen=True
)


def log_distance_score(room: RoomHypothesis, target: dict[str, float] = TARGET) -> float:
    """Highest at `target`, falling with each field's log distance from it."""
    return -sum(math.log(getattr(room, f) / v) ** 2 for f, v in target.items())


def worst_log_error(room: RoomHypothesis) -> float:
    return max(abs(math.log(getattr(room, f) / v)) for f, v in TARGET.items())


def test_the_fine_steps_reach_between_the_grid_values(monkeypatch: pytest.MonkeyPatch) -> None:
    found = coordinate_search(START, log_distance_score, GRIDS)
    assert worst_log_error(found) < 0.02  # within the finest step
    assert found.score == pytest.approx(log_distance_score(found))
    assert found.back == START.back  # not searched

    monkeypatch.setattr(room_layout, "FINE_STEPS", ())
    grid_only = coordinate_search(START, log_distance_score, GRIDS)
    assert worst_log_error(grid_only) > 0.02  # the grid's steps are 11-17%
    assert all(any(math.isclose(getattr(grid_only, f), v) for v in GRIDS[f]) for f in TARGET)


def test_the_fine_steps_never_leave_the_grid_range() -> None:
    # The best front wall lies below the grid's range (say, inside the floor's objects).
    def score(room: RoomHypothesis) -> float:
        return log_distance_score(room, {**TARGET, "front": 0.3})

    found = coordinate_search(START, score, GRIDS)
    assert found.front >= GRIDS["front"][0]
    assert found.front < GRIDS["front"][0] * math.exp(0.02)
