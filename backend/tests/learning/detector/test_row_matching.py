"""Raw detector rows of two runtimes matched with near-ties allowed to swap."""

from __future__ import annotations

import math

import numpy as np
from holiscene.learning.detector.row_matching import rows_difference, unmatched_rows

RAW_TOL = 1e-4


def test_row_matching_allows_near_ties_only() -> None:
    rows = np.array(
        [[0, 0, 10, 10, 0.5, 1], [0, 0, 20, 20, 0.49999, 2], [5, 5, 9, 9, 0.3, 1]],
        dtype=np.float64,
    )
    assert unmatched_rows(rows, rows, RAW_TOL) == []
    assert unmatched_rows(rows[[1, 0, 2]], rows, RAW_TOL) == []  # scores 1e-5 apart
    assert unmatched_rows(rows[[0, 2, 1]], rows, RAW_TOL) != []  # 0.3 is not near 0.49999
    moved = rows.copy()
    moved[0, 2] += 0.1  # a corner off by 0.1 input pixels: 2e-4 of the input size
    assert unmatched_rows(moved, rows, RAW_TOL) == ["actual row 0", "expected row 0"]
    other = rows.copy()
    other[0, 5] = 3
    assert unmatched_rows(other, rows, RAW_TOL) != []


def test_the_export_measure_is_the_largest_partner_difference_or_infinite() -> None:
    rows = np.array(
        [[0, 0, 10, 10, 0.5, 1], [0, 0, 20, 20, 0.49999, 2], [5, 5, 9, 9, 0.3, 1]],
        dtype=np.float64,
    )
    measure = rows_difference(RAW_TOL)
    swapped = rows[[1, 0, 2]].copy()
    swapped[0, 4] += 2e-6
    assert abs(measure(swapped, rows) - 2e-6) < 1e-12
    moved = rows.copy()
    moved[0, 3] += 5.0  # far from the cut (the last row's score): no excuse
    assert measure(moved, rows) == math.inf


def test_a_peak_of_a_flat_heatmap_may_be_on_one_side_only() -> None:
    """Two neighbouring cells of one class and score: whether both are peaks is decided in
    the last bits, so a row with a same-class, same-score twin may have no partner."""
    expected = np.array(
        [[0, 0, 10, 10, 0.5, 1], [40, 40, 90, 90, 0.2, 4], [5, 5, 9, 9, 0.1, 1]],
        dtype=np.float64,
    )
    twin = [44, 40, 94, 92, 0.2 + 1e-6, 4]  # the next cell on, of the same score
    actual = np.array([expected[0], twin, expected[1]], dtype=np.float64)
    assert unmatched_rows(actual, expected, RAW_TOL) == []
    other_class = np.array([expected[0], [*twin[:5], 3], expected[1]], dtype=np.float64)
    assert unmatched_rows(other_class, expected, RAW_TOL) == ["actual row 1"]
