"""Mask run-length encoding round trips."""

from __future__ import annotations

import numpy as np
from holiscene.segmentation.rle import decode_mask, encode_mask
from hypothesis import given, settings
from hypothesis import strategies as st
from hypothesis.extra.numpy import arrays


@settings(max_examples=80, deadline=None)
@given(arrays(np.bool_, st.tuples(st.integers(1, 24), st.integers(1, 24))))
def test_encode_then_decode(mask: np.ndarray) -> None:
    encoded = encode_mask(mask, "box")
    if not mask.any():
        assert encoded is None
        return
    assert encoded is not None
    assert sum(encoded.rle) == encoded.size[0] * encoded.size[1]
    assert np.array_equal(decode_mask(encoded, mask.shape[1], mask.shape[0]), mask)


def test_window_is_tight() -> None:
    mask = np.zeros((10, 12), dtype=bool)
    mask[2:5, 3:7] = True
    encoded = encode_mask(mask, "box")
    assert encoded is not None
    assert (encoded.origin, encoded.size, encoded.rle) == ([3, 2], [4, 3], [0, 12])
