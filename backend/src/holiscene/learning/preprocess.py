"""The Relation Network's inputs from a photo and its objects, exactly as the contract says.

The browser computes the same tensors (frontend/src/inference/preprocess.ts); the shared
vectors in shared_schema/vectors/relation_model.json keep the two in step.
"""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np
from holiscene_schema import NYU40_CLASSES
from holiscene_schema.relation_model import IMAGE_SIZE, MASK_SIZE

_CLASS_INDEX = {name: i for i, name in enumerate(NYU40_CLASSES)}


def cell_bounds(length: int, cells: int) -> tuple[np.ndarray, np.ndarray]:
    """Start (inclusive) and end (exclusive) input index of each output cell; never empty."""
    starts = (np.arange(cells) * length) // cells
    ends = np.maximum((np.arange(1, cells + 1) * length) // cells, starts + 1)
    return starts, np.minimum(ends, length)


def area_resize(values: np.ndarray, size: int, divisor: float = 1.0) -> np.ndarray:
    """Mean of each cell of an (H, W) or (H, W, C) array on a size x size grid, divided by
    `divisor` (in float64, rounded once to float32).

    Cells tile the input when shrinking, so one `reduceat` per axis sums them; when growing
    a cell is one input row or column, which `reduceat` returns as it is. Integer and bool
    inputs are summed exactly in int64, everything else in float64."""
    height, width = values.shape[:2]
    r0, r1 = cell_bounds(height, size)
    c0, c1 = cell_bounds(width, size)
    exact = values.dtype == np.bool_ or np.issubdtype(values.dtype, np.integer)
    accumulate = np.int64 if exact else np.float64
    sums = np.add.reduceat(np.add.reduceat(values, r0, axis=0, dtype=accumulate), c0, axis=1)
    counts = (r1 - r0)[:, None] * (c1 - c0)[None, :] * divisor
    if values.ndim == 3:
        counts = counts[:, :, None]
    out: np.ndarray = (sums / counts).astype(np.float32)
    return out


def mask_resize(mask: np.ndarray, size: int) -> np.ndarray:
    """`area_resize` of a bool mask, summing only the cells its bounding box touches (an
    object covers a small part of the photo, so this is most of the preprocessing time)."""
    rows = np.flatnonzero(mask.any(axis=1))
    cols = np.flatnonzero(mask.any(axis=0))
    out = np.zeros((size, size), dtype=np.float32)
    if len(rows) == 0:
        return out
    (r0, r1), (c0, c1) = cell_bounds(mask.shape[0], size), cell_bounds(mask.shape[1], size)
    # Cells that overlap the box: their start is before its end and their end after its start.
    rs = np.flatnonzero((r0 <= rows[-1]) & (r1 > rows[0]))
    cs = np.flatnonzero((c0 <= cols[-1]) & (c1 > cols[0]))
    window = mask[r0[rs[0]] : r1[rs[-1]], c0[cs[0]] : c1[cs[-1]]]
    sums = np.add.reduceat(
        np.add.reduceat(window, r0[rs] - r0[rs[0]], axis=0, dtype=np.int64),
        c0[cs] - c0[cs[0]],
        axis=1,
        dtype=np.int64,
    )
    counts = (r1[rs] - r0[rs])[:, None] * (c1[cs] - c0[cs])[None, :]
    out[rs[0] : rs[-1] + 1, cs[0] : cs[-1] + 1] = sums / counts
    return out


def class_index(cls: str) -> int:
    return _CLASS_INDEX[cls]


def relation_inputs(
    image: np.ndarray,
    masks: Sequence[np.ndarray],
    boxes: Sequence[Sequence[float]],
    classes: Sequence[str],
) -> dict[str, np.ndarray]:
    """The model's input tensors: `image` RGB uint8 (H, W, 3), one bool (H, W) mask, box
    (x0, y0, x1, y1) in pixels and NYU-40 class per object."""
    if not (len(masks) == len(boxes) == len(classes)) or not masks:
        raise ValueError("relation inputs need one mask, box and class per object, at least one")
    height, width = image.shape[:2]
    rgb = area_resize(image, IMAGE_SIZE, divisor=255.0)
    scale = np.array([width, height, width, height], dtype=np.float64)
    return {
        "image": np.ascontiguousarray(rgb.transpose(2, 0, 1)[None], dtype=np.float32),
        "masks": np.stack([mask_resize(m, MASK_SIZE) for m in masks]),
        "boxes": (np.asarray(boxes, dtype=np.float64) / scale).astype(np.float32),
        "classes": np.array([class_index(c) for c in classes], dtype=np.int64),
    }
