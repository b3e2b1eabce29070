"""Two runs of a detector's raw rows compared as people would: near-ties may swap.

A detector's output rows (holiscene_schema.detector_model) are its peaks best first. Two
runtimes (PyTorch and onnxruntime, onnxruntime and onnxruntime-web) compute scores that differ
in the last bits, so peaks whose scores are closer than the tolerance may come in another
order, and the last rows may be others when their scores are that close to the cut; a row
of the same class and score as another may be there on one side only (two neighbouring
cells of one value: a peak or not, by the last bits). An untrained net, whose peaks all sit
near its prior, is full of such ties. The same rule is
matchRows in e2e_tests/tests/detector-model.spec.ts.
"""

from __future__ import annotations

import math
from collections.abc import Callable

import numpy as np
from holiscene_schema.detector_model import INPUT_SIZE


def row_difference(a: np.ndarray, b: np.ndarray) -> float:
    """Box corners as shares of the input size, scores as they are, class indices exactly."""
    if a[5] != b[5]:
        return math.inf
    return float(max(np.abs(a[:4] - b[:4]).max() / INPUT_SIZE, abs(a[4] - b[4])))


def match_rows(actual: np.ndarray, expected: np.ndarray, tol: float) -> tuple[list[str], float]:
    """The rows of either side without a partner on the other (empty: they match), and the
    largest difference between partners."""
    a, e = actual.reshape(-1, 6), expected.reshape(-1, 6)
    partner = [i if row_difference(a[i], e[i]) <= tol else -1 for i in range(len(a))]
    taken = {j for j in partner if j >= 0}
    for i in (i for i in range(len(a)) if partner[i] < 0):
        # Anywhere on the other side: a row one side has and the other has not (below) moves
        # the rows after it by one. The order itself is checked on its own.
        near = [j for j in range(len(e)) if j not in taken and row_difference(a[i], e[j]) <= tol]
        if near:
            partner[i] = min(near, key=lambda j: abs(j - i))
            taken.add(partner[i])
    cut = e[-1][4]

    def explained(rows: np.ndarray, i: int) -> bool:
        """A row whose score is that close to the cut, or to another row's of its class: a
        weakly trained head's flat heatmap has neighbouring cells of one score, and which of
        them count as peaks is decided in the last bits."""
        same = (rows[:, 5] == rows[i][5]) & (np.abs(rows[:, 4] - rows[i][4]) <= tol)
        return abs(rows[i][4] - cut) <= tol or int(same.sum()) > 1

    left = [f"actual row {i}" for i in range(len(a)) if partner[i] < 0 and not explained(a, i)]
    left += [f"expected row {j}" for j in range(len(e)) if j not in taken and not explained(e, j)]
    for side, rows in (("actual", a), ("expected", e)):
        rising = np.flatnonzero(np.diff(rows[:, 4]) > tol) + 1
        left += [f"{side} row {i} out of score order" for i in rising]
    largest = max(
        (row_difference(a[i], e[j]) for i, j in enumerate(partner) if j >= 0), default=0.0
    )
    return left, largest


def unmatched_rows(actual: np.ndarray, expected: np.ndarray, tol: float) -> list[str]:
    return match_rows(actual, expected, tol)[0]


def rows_difference(tol: float) -> Callable[[np.ndarray, np.ndarray], float]:
    """keep_if_faithful's measure for detector rows: the largest difference between partners,
    or infinity when a row has none."""

    def difference(actual: np.ndarray, expected: np.ndarray) -> float:
        left, largest = match_rows(actual, expected, tol)
        return math.inf if left else largest

    return difference
