"""Decoding network scores into a support tree."""

from __future__ import annotations

import numpy as np
from holiscene.learning.decode import decode_supports, ranked_candidates
from holiscene.learning.priors import count_priors
from holiscene.learning.samples import NO_LABEL, SupportSample, answer_index
from holiscene_schema import SupportRelation, support_graph_problems


def _probabilities(n: int, picks: dict[int, list[tuple[int, int, float]]]) -> np.ndarray:
    """Rows with the given (column, type index, probability); the rest spread evenly."""
    table = np.full((n, n + 3, 2), 1e-3)
    for row, entries in picks.items():
        for column, kind, p in entries:
            table[row, column, kind] = p
    return table / table.reshape(n, -1).sum(1)[:, None, None]


def test_each_object_gets_its_most_probable_supporter() -> None:
    ids, classes = ["o0", "o1"], ["lamp", "table"]
    table = _probabilities(2, {0: [(1, 0, 0.9)], 1: [(3, 0, 0.95)]})  # lamp on table, floor
    supports = decode_supports(table, ids, classes)
    assert [(s.child, s.parent, s.type) for s in supports] == [
        ("o0", "o1", "below"),
        ("o1", "floor", "below"),
    ]
    assert supports[0].source == "auto" and 0.8 < (supports[0].confidence or 0) <= 1


def test_the_room_holds_things_up_one_way_only_whatever_the_network_says() -> None:
    # Columns n..n+2 are ceiling, floor, wall; types 0 below, 1 behind. The network's best
    # answers are "floor, behind" for o0 and "wall, below" for o1, which no room part does.
    ids, classes = ["o0", "o1"], ["chair", "picture"]
    table = _probabilities(2, {0: [(3, 1, 0.8), (3, 0, 0.1)], 1: [(4, 0, 0.7), (4, 1, 0.2)]})
    supports = decode_supports(table, ids, classes)
    assert [(s.child, s.parent, s.type) for s in supports] == [
        ("o0", "floor", "below"),
        ("o1", "wall", "behind"),
    ]
    for row in range(2):
        ranked = ranked_candidates(table, row, ids, classes)
        impossible = {("floor", "behind"), ("wall", "below"), ("ceiling", "below")}
        assert all(score == 0 for score, parent, kind in ranked if (parent, kind) in impossible)
        assert abs(sum(score for score, _, _ in ranked) - 1) < 1e-9


def test_a_cycle_is_broken_by_the_less_confident_object() -> None:
    ids, classes = ["o0", "o1"], ["box", "box"]
    # o0 on o1 (0.9) and o1 on o0 (0.6): o1 must take its next choice, the floor.
    table = _probabilities(2, {0: [(1, 0, 0.9)], 1: [(0, 0, 0.6), (3, 0, 0.3)]})
    supports = decode_supports(table, ids, classes)
    assert not support_graph_problems(ids, [(s.child, s.parent) for s in supports])
    assert {s.child: s.parent for s in supports} == {"o0": "o1", "o1": "floor"}


def test_pinned_supports_are_kept_and_respected() -> None:
    ids, classes = ["o0", "o1"], ["box", "box"]
    pinned = SupportRelation(child="o1", parent="o0", type="below", source="manual", author="a")
    table = _probabilities(2, {0: [(1, 0, 0.9)], 1: [(3, 0, 0.9)]})
    supports = decode_supports(table, ids, classes, [pinned])
    assert supports[1] == pinned
    assert supports[0].parent != "o1"  # o0 on o1 would close a cycle with the pinned edge


def test_priors_overrule_an_implausible_category() -> None:
    classes = ("lamp", "table", "picture")
    sample = SupportSample(
        "s",
        {},
        ("o0", "o1", "o2"),
        classes,
        np.array([answer_index(1, "below"), answer_index(4, "below"), NO_LABEL]),
    )
    priors = count_priors([sample] * 5)
    # The network slightly prefers the picture as the lamp's supporter.
    table = _probabilities(3, {0: [(2, 0, 0.45), (1, 0, 0.40)]})
    network = ranked_candidates(table, 0, ["o0", "o1", "o2"], classes)
    combined = ranked_candidates(table, 0, ["o0", "o1", "o2"], classes, priors, "network+priors")
    assert network[0][1] == "o2"
    assert combined[0][1] == "o1"
