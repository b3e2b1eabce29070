"""What the layout and object networks read of a photo (numpy and onnxruntime, shared by
training and run time): the COCO detector's backbone (`detector.backbone`) run once, its deep
features (480 channels at a 32nd of the input) with the neck's (128 channels at a quarter,
averaged down to the same grid) for the whole room, and per object its 2D box's share of
both (the neck's on a 4 x 4 grid inside the box, the deep features averaged over it), the
box's place in the camera's view and its class."""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np
from holiscene_schema import NYU40_CLASSES
from numpy.typing import NDArray

from ..detector.backbone import DEEP_CHANNELS, FEATURE_CHANNELS, FeatureExtractor
from ..detector.runtime import preprocess

Float32Array = NDArray[np.float32]

ROI_GRID = 4  # neck cells per side of an object's pooled window
OBJECT_APPEARANCE = FEATURE_CHANNELS * ROI_GRID * ROI_GRID + DEEP_CHANNELS
OBJECT_GEOMETRY = 10  # the 2D box in the camera's view, its size, and where the photo cuts it
OBJECT_INPUTS = OBJECT_APPEARANCE + OBJECT_GEOMETRY + len(NYU40_CLASSES)
ROOM_CHANNELS = DEEP_CHANNELS + FEATURE_CHANNELS
CAMERA_INPUTS = 4  # focal length, principal point and aspect
_EDGE_PX = 2.0


@dataclass(frozen=True)
class PhotoFeatures:
    room: Float32Array  # (ROOM_CHANNELS, G, G), G = the deep grid
    camera: Float32Array  # (CAMERA_INPUTS,)
    objects: Float32Array  # (n, OBJECT_INPUTS)


def _window_mean(grid: Float32Array, box: Sequence[float]) -> Float32Array:
    """The mean of a (C, H, W) map over the cells a box (cell units) touches; at least one."""
    _, rows, cols = grid.shape
    x0 = min(max(math.floor(box[0]), 0), cols - 1)
    y0 = min(max(math.floor(box[1]), 0), rows - 1)
    x1 = max(min(math.ceil(box[2]), cols), x0 + 1)
    y1 = max(min(math.ceil(box[3]), rows), y0 + 1)
    result: Float32Array = grid[:, y0:y1, x0:x1].mean(axis=(1, 2))
    return result


def _roi(grid: Float32Array, box: Sequence[float]) -> Float32Array:
    """The map's means over a ROI_GRID x ROI_GRID split of the box (cell units), flattened."""
    xs = np.linspace(box[0], box[2], ROI_GRID + 1)
    ys = np.linspace(box[1], box[3], ROI_GRID + 1)
    cells = [
        _window_mean(grid, (xs[j], ys[i], xs[j + 1], ys[i + 1]))
        for i in range(ROI_GRID)
        for j in range(ROI_GRID)
    ]
    return np.stack(cells, axis=1).reshape(-1)


def box_geometry(
    bbox: Sequence[float], K: NDArray[np.float64], width: int, height: int
) -> Float32Array:
    f, cx, cy = float(K[0, 0]), float(K[0, 2]), float(K[1, 2])
    x1, y1, x2, y2 = bbox
    return np.array(
        [
            (x1 - cx) / f,
            (y1 - cy) / f,
            (x2 - cx) / f,
            (y2 - cy) / f,
            math.log(max(x2 - x1, 1.0) / f),
            math.log(max(y2 - y1, 1.0) / f),
            float(x1 <= _EDGE_PX),
            float(y1 <= _EDGE_PX),
            float(x2 >= width - _EDGE_PX),
            float(y2 >= height - _EDGE_PX),
        ],
        dtype=np.float32,
    )


def camera_inputs(K: NDArray[np.float64], width: int, height: int) -> Float32Array:
    return np.array(
        [
            math.log(float(K[0, 0]) / width),
            float(K[0, 2]) / width - 0.5,
            float(K[1, 2]) / height - 0.5,
            math.log(height / width),
        ],
        dtype=np.float32,
    )


def photo_features(
    extractor: FeatureExtractor,
    rgb: NDArray[np.uint8],
    K: NDArray[np.float64],
    boxes: Sequence[Sequence[float]],
    classes: Sequence[str],
) -> PhotoFeatures:
    """The networks' inputs for a photo and its objects' 2D boxes (photo pixels) and classes."""
    height, width = rgb.shape[:2]
    neck, _, deep = extractor(preprocess(rgb))
    neck, deep = neck[0].astype(np.float32), deep[0].astype(np.float32)
    grid = deep.shape[1]
    factor = neck.shape[1] // grid
    pooled = neck.reshape(neck.shape[0], grid, factor, grid, factor).mean(axis=(2, 4))
    room = np.concatenate([deep, pooled]).astype(np.float32)
    to_neck = np.array([width, height, width, height], dtype=float) / neck.shape[1]
    to_deep = np.array([width, height, width, height], dtype=float) / grid
    class_index = {name: i for i, name in enumerate(NYU40_CLASSES)}
    rows = []
    for bbox, cls in zip(boxes, classes, strict=True):
        one_hot = np.zeros(len(NYU40_CLASSES), np.float32)
        if cls in class_index:
            one_hot[class_index[cls]] = 1.0
        rows.append(
            np.concatenate(
                [
                    _roi(neck, np.asarray(bbox, dtype=float) / to_neck),
                    _window_mean(deep, np.asarray(bbox, dtype=float) / to_deep),
                    box_geometry(bbox, K, width, height),
                    one_hot,
                ]
            )
        )
    objects = (
        np.stack(rows).astype(np.float32) if rows else np.zeros((0, OBJECT_INPUTS), np.float32)
    )
    return PhotoFeatures(room, camera_inputs(K, width, height), objects)
