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


def area_resize(values: np.ndarray, size: int) -> np.ndarray:
    """Mean of each cell of an (H, W) or (H, W, C) array on a size x size grid, as float32."""
    data = values.astype(np.float64)
    if data.ndim == 2:
        data = data[:, :, None]
    height, width = data.shape[:2]
    # Integral image with a zero first row and column: any cell sum is four look-ups.
    integral = np.zeros((height + 1, width + 1, data.shape[2]), dtype=np.float64)
    integral[1:, 1:] = data.cumsum(axis=0).cumsum(axis=1)
    r0, r1 = cell_bounds(height, size)
    c0, c1 = cell_bounds(width, size)
    sums = integral[r1][:, c1] - integral[r0][:, c1] - integral[r1][:, c0] + integral[r0][:, c0]
    counts = ((r1 - r0)[:, None] * (c1 - c0)[None, :])[:, :, None]
    out: np.ndarray = (sums / counts).astype(np.float32)
    return out[:, :, 0] if values.ndim == 2 else out


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
    rgb = area_resize(image.astype(np.float64) / 255.0, IMAGE_SIZE)
    scale = np.array([width, height, width, height], dtype=np.float64)
    return {
        "image": np.ascontiguousarray(rgb.transpose(2, 0, 1)[None], dtype=np.float32),
        "masks": np.stack([area_resize(m, MASK_SIZE) for m in masks]).astype(np.float32),
        "boxes": (np.asarray(boxes, dtype=np.float64) / scale).astype(np.float32),
        "classes": np.array([class_index(c) for c in classes], dtype=np.int64),
    }
