"""The box refiner's room cache: a longer training run makes only the rooms an earlier one
did not, and never mixes in rooms made for other features."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest
from holiscene.learning.box_refiner.data import RoomCache, RoomSample, make_rooms
from holiscene.shapes import SIZE_RANGES

CLASSES = sorted(SIZE_RANGES)


def _marked_sample(seed: int, missed: int) -> RoomSample:
    """A sample no pipeline would make (no objects, an odd count of missed boxes), so the
    test can tell a cached room from a made one."""
    return RoomSample(
        seed=seed,
        features=np.zeros((0, 3), np.float32),
        pairs=np.zeros((0, 0, 4), np.float32),
        targets=np.zeros((0, 4), np.float32),
        estimates=[],
        truths=[],
        missed=missed,
    )


def test_cached_rooms_are_read_back_and_only_the_others_are_made(tmp_path: Path) -> None:
    cache = RoomCache(tmp_path / "rooms", CLASSES)
    cache.put(_marked_sample(610000, missed=97))
    rooms = list(make_rooms([610000, 610001], CLASSES, workers=1, cache=cache))
    assert [r.seed for r in rooms if isinstance(r, RoomSample)] == [610000, 610001]
    first, second = rooms
    assert isinstance(first, RoomSample) and first.missed == 97  # read, not made again
    assert isinstance(second, RoomSample) and len(second.truths) > 0  # made by the pipeline
    # The room just made is kept: a second cache on the same folder has both.
    again = RoomCache(tmp_path / "rooms", CLASSES)
    kept = again.get(610001)
    assert kept is not None and np.array_equal(kept.targets, second.targets)
    assert not list((tmp_path / "rooms").glob("*.tmp"))


def test_a_cache_made_for_other_classes_is_refused(tmp_path: Path) -> None:
    RoomCache(tmp_path / "rooms", CLASSES)
    with pytest.raises(ValueError, match="other classes, features or stages"):
        RoomCache(tmp_path / "rooms", CLASSES[:-1])
