"""What every dataset reader yields: one item per photo, its checked inputs or why not, and
the helpers the readers share (a polygon's mask, a labelled box as a Detection)."""

from __future__ import annotations

import json
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np
from PIL import Image, ImageDraw

from ...pipeline.base import Detection
from ...segmentation.rle import encode_mask
from ..validation import InputError, InputFiles, detection_from_item, parse_class_map

CLASS_MAP_FILE = "class_map.json"


@dataclass(frozen=True)
class DatasetItem:
    """One photo of a dataset: `inputs` when it reads, else `error` says why (nothing of it
    is imported then). `name` names it for the user (the image's file name)."""

    name: str
    inputs: InputFiles | None = None
    error: str | None = None


def load_json(path: Path) -> Any:
    try:
        data = path.read_bytes()
    except OSError as exc:
        raise InputError(f"{path.name} cannot be read: {exc.strerror or exc}") from exc
    try:
        return json.loads(data)
    except (json.JSONDecodeError, UnicodeDecodeError, RecursionError) as exc:
        raise InputError(f"{path.name} is not valid JSON: {exc}") from exc


def class_map_beside(path: Path) -> dict[str, str] | None:
    """The user's class names (class_map.json) in the folder of a dataset file, if any."""
    file = path.parent / CLASS_MAP_FILE
    return parse_class_map(file.read_bytes()) if file.is_file() else None


def polygon_pixels(where: str, flat: Any, width: int, height: int) -> np.ndarray:
    """The bool (H, W) mask inside a polygon [x1, y1, x2, y2, ...] in pixel coordinates."""
    if (
        not isinstance(flat, list)
        or len(flat) % 2
        or not all(isinstance(v, int | float) and not isinstance(v, bool) for v in flat)
    ):
        raise InputError(f"{where}: a polygon must be a flat list of x, y numbers")
    if len(flat) < 6:
        raise InputError(f"{where}: a polygon needs at least 3 points, it has {len(flat) // 2}")
    canvas = Image.new("1", (width, height), 0)
    corners = [(float(x), float(y)) for x, y in zip(flat[::2], flat[1::2], strict=True)]
    ImageDraw.Draw(canvas).polygon(corners, fill=1)
    return np.asarray(canvas, dtype=bool)


def labelled_detection(
    where: str,
    name: Any,
    bbox_xyxy: list[float] | None,
    pixels: np.ndarray | None,
    width: int,
    height: int,
    class_map: dict[str, str] | None,
) -> Detection:
    """A labelled object as a Detection with its mask (source "given"): the box given, or the
    mask's bounding box when none is; checked as detections.json items are."""
    mask = encode_mask(pixels, "given") if pixels is not None else None
    if bbox_xyxy is None:
        if mask is None:
            raise InputError(f"{where}: the object's outline covers no pixel")
        (x0, y0), (w, h) = mask.origin, mask.size
        bbox_xyxy = [float(x0), float(y0), float(x0 + w), float(y0 + h)]
    item: dict[str, Any] = {"bbox": bbox_xyxy, "class": name}
    if mask is not None:
        item["mask"] = mask
    return detection_from_item(where, item, width, height, class_map or {})
