"""What every dataset reader yields: one item per photo, its checked inputs or why not, and
the helpers the readers share (a polygon's mask, a labelled box as a Detection)."""

from __future__ import annotations

import json
from collections.abc import Iterator
from contextlib import contextmanager
from contextvars import ContextVar
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


# The unpacked upload a server is importing: the files a dataset names (COCO's file_name,
# LabelMe's imagePath) must lie inside it, so an upload cannot make a photo of any image the
# server can read ("../../", an absolute path). None on the command line: the user's files.
_UPLOAD_ROOT: ContextVar[Path | None] = ContextVar("holiscene_upload_root", default=None)


@contextmanager
def confined_to(root: Path) -> Iterator[None]:
    """Dataset readers in this block refuse files named outside `root`."""
    token = _UPLOAD_ROOT.set(root.resolve())
    try:
        yield
    finally:
        _UPLOAD_ROOT.reset(token)


def named_file(candidate: Path, name: str) -> Path | None:
    """A file a dataset names by `name`, as found at `candidate`: None when there is none
    there; InputError when it lies outside the upload being imported."""
    if not candidate.is_file():
        return None
    root = _UPLOAD_ROOT.get()
    if root is not None and not candidate.resolve().is_relative_to(root):
        raise InputError(f"{name} points outside the uploaded files")
    return candidate


def class_map_beside(path: Path) -> dict[str, str] | None:
    """The user's class names (class_map.json) in the folder of a dataset file, if any."""
    file = path.parent / CLASS_MAP_FILE
    return parse_class_map(file.read_bytes()) if file.is_file() else None


def polygon_pixels(
    where: str, flat: Any, width: int, height: int, *, at_pixel_centres: bool = False
) -> np.ndarray:
    """The bool (H, W) mask inside a polygon [x1, y1, x2, y2, ...] in pixel coordinates.

    By default as LabelMe and PIL fill one: every pixel the outline touches is in. With
    `at_pixel_centres`, as COCO's own tools rasterise: a pixel is in when its centre (x + 0.5,
    y + 0.5) is inside, so a small object's mask is not a ring of pixels too large."""
    if (
        not isinstance(flat, list)
        or len(flat) % 2
        or not all(isinstance(v, int | float) and not isinstance(v, bool) for v in flat)
    ):
        raise InputError(f"{where}: a polygon must be a flat list of x, y numbers")
    if len(flat) < 6:
        raise InputError(f"{where}: a polygon needs at least 3 points, it has {len(flat) // 2}")
    corners = [(float(x), float(y)) for x, y in zip(flat[::2], flat[1::2], strict=True)]
    if at_pixel_centres:
        return _centres_inside(np.array(corners), width, height)
    canvas = Image.new("1", (width, height), 0)
    ImageDraw.Draw(canvas).polygon(corners, fill=1)
    return np.asarray(canvas, dtype=bool)


def _centres_inside(corners: np.ndarray, width: int, height: int) -> np.ndarray:
    """The pixels whose centre is inside the polygon (even-odd rule): each edge flips the
    pixels left of it on the rows whose centre line it crosses."""
    out = np.zeros((height, width), dtype=bool)
    x0, y0 = np.floor(corners.min(axis=0)).astype(int).clip(0, [width, height])
    x1, y1 = np.ceil(corners.max(axis=0)).astype(int).clip(0, [width, height])
    if x0 >= x1 or y0 >= y1:
        return out
    centres_x = np.arange(x0, x1) + 0.5
    inside = np.zeros((y1 - y0, x1 - x0), dtype=bool)
    for (ax, ay), (bx, by) in zip(corners, np.roll(corners, -1, axis=0), strict=True):
        low, high = min(ay, by), max(ay, by)
        # The rows whose centre y + 0.5 lies in [low, high): a horizontal edge has none.
        first = max(int(np.ceil(low - 0.5)) - y0, 0)
        last = min(int(np.ceil(high - 0.5)) - y0, y1 - y0)
        if first >= last:
            continue
        rows_y = np.arange(first, last) + y0 + 0.5
        crossing_x = ax + (rows_y - ay) * (bx - ax) / (by - ay)
        inside[first:last] ^= centres_x[None, :] < crossing_x[:, None]
    out[y0:y1, x0:x1] = inside
    return out


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
