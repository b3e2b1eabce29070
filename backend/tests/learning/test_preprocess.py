"""The Relation Network's preprocessing follows the contract's arithmetic exactly."""

from __future__ import annotations

import numpy as np
import pytest
from holiscene.learning.preprocess import area_resize, cell_bounds, mask_resize, relation_inputs
from holiscene_schema.relation_model import IMAGE_SIZE, MASK_SIZE


def test_cell_bounds_cover_every_row_once_when_shrinking() -> None:
    starts, ends = cell_bounds(530, 64)
    assert starts[0] == 0 and ends[-1] == 530
    assert np.all(ends[:-1] == starts[1:])


def test_cell_bounds_never_empty_when_growing() -> None:
    starts, ends = cell_bounds(30, 64)
    assert np.all(ends > starts) and ends.max() == 30


def test_area_resize_is_the_mean_of_each_cell() -> None:
    rng = np.random.default_rng(3)
    values = rng.random((97, 61))
    out = area_resize(values, 8)
    rows, cols = cell_bounds(97, 8), cell_bounds(61, 8)
    for r in range(8):
        for c in range(8):
            block = values[rows[0][r] : rows[1][r], cols[0][c] : cols[1][c]]
            assert out[r, c] == pytest.approx(block.mean(), abs=1e-6)


def test_relation_inputs_shapes_dtypes_and_values() -> None:
    image = np.zeros((40, 50, 3), dtype=np.uint8)
    image[:, :, 0] = 255
    mask = np.zeros((40, 50), dtype=bool)
    mask[:20, :25] = True  # the top-left quarter
    boxes = [[0, 0, 25, 20], [0, 0, 50, 40]]
    inputs = relation_inputs(image, [mask, ~mask], boxes, ["lamp", "table"])
    assert inputs["image"].shape == (1, 3, IMAGE_SIZE, IMAGE_SIZE)
    assert inputs["image"].dtype == np.float32
    assert np.all(inputs["image"][0, 0] == 1.0) and np.all(inputs["image"][0, 1] == 0.0)
    assert inputs["masks"].shape == (2, MASK_SIZE, MASK_SIZE)
    assert inputs["masks"][0].mean() == pytest.approx(0.25, abs=0.02)
    assert inputs["masks"][0, 0, 0] == 1.0 and inputs["masks"][0, -1, -1] == 0.0
    np.testing.assert_allclose(inputs["boxes"][0], [0, 0, 0.5, 0.5])
    assert inputs["classes"].dtype == np.int64
    assert inputs["classes"].tolist() == [34, 6]


def test_relation_inputs_refuse_mismatched_lists() -> None:
    image = np.zeros((10, 10, 3), dtype=np.uint8)
    with pytest.raises(ValueError, match="one mask, box and class"):
        relation_inputs(image, [np.ones((10, 10), bool)], [], ["lamp"])


def test_mask_resize_equals_area_resize() -> None:
    rng = np.random.default_rng(5)
    for height, width in [(480, 640), (30, 50), (97, 61)]:
        for _ in range(5):
            mask = np.zeros((height, width), dtype=bool)
            y0, x0 = rng.integers(0, height), rng.integers(0, width)
            y1, x1 = rng.integers(y0, height) + 1, rng.integers(x0, width) + 1
            mask[y0:y1, x0:x1] = rng.random((y1 - y0, x1 - x0)) < 0.7
            np.testing.assert_array_equal(
                mask_resize(mask, MASK_SIZE), area_resize(mask, MASK_SIZE)
            )
    assert not mask_resize(np.zeros((20, 20), dtype=bool), MASK_SIZE).any()
