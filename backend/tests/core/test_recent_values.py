"""RecentValues keeps the most recently used values, up to its size."""

from __future__ import annotations

import pytest
from holiscene.core.recent_values import RecentValues


def test_the_least_recently_used_value_goes_first() -> None:
    recent: RecentValues[str, int] = RecentValues(2)
    recent.put("a", 1)
    recent.put("b", 2)
    assert recent.get("a") == 1  # now b is the oldest
    recent.put("c", 3)
    assert (recent.get("a"), recent.get("b"), recent.get("c")) == (1, None, 3)
    recent.put("a", 4)  # a new value for a key keeps one entry
    recent.put("d", 5)
    assert (recent.get("a"), recent.get("c"), recent.get("d")) == (4, None, 5)


def test_it_keeps_at_least_one() -> None:
    with pytest.raises(ValueError):
        RecentValues(0)
