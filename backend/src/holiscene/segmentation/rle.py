"""Binary masks <-> the contract's windowed run-length encoding (rows, starting with 0s)."""

from __future__ import annotations

import numpy as np
from holiscene_schema import Mask, MaskSource


def encode_mask(mask: np.ndarray, source: MaskSource) -> Mask | None:
    """Encode the tight window around a full-image bool mask; None for an empty mask."""
    rows = np.flatnonzero(mask.any(axis=1))
    cols = np.flatnonzero(mask.any(axis=0))
    if len(rows) == 0:
        return None
    y0, y1, x0, x1 = int(rows[0]), int(rows[-1]) + 1, int(cols[0]), int(cols[-1]) + 1
    flat = mask[y0:y1, x0:x1].reshape(-1).astype(np.int8)
    change = np.flatnonzero(np.diff(flat)) + 1
    bounds = np.concatenate([[0], change, [flat.size]])
    runs = np.diff(bounds).tolist()
    if flat[0]:  # runs must start with a (here empty) run of zeros
        runs = [0, *runs]
    return Mask(origin=[x0, y0], size=[x1 - x0, y1 - y0], rle=runs, source=source)


def decode_mask(mask: Mask, width: int, height: int) -> np.ndarray:
    """The full-image bool mask (height, width)."""
    w, h = mask.size
    flat = np.zeros(w * h, dtype=bool)
    position, value = 0, False
    for run in mask.rle:
        if value:
            flat[position : position + run] = True
        position += run
        value = not value
    out = np.zeros((height, width), dtype=bool)
    x0, y0 = mask.origin
    out[y0 : y0 + h, x0 : x0 + w] = flat.reshape(h, w)[: height - y0, : width - x0]
    return out
