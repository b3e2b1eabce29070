"""LabelMe files: one JSON per photo, `shapes` of {label, points, shape_type, group_id}, the
photo at `imagePath` (relative to the JSON, `/` or `\\` separated) or embedded as `imageData`
(base64). LabelMe's own reading of them decides:

- shapes of one label and one `group_id` are one object (the parts of an object seen in
  pieces); a shape without a group is an object of its own;
- polygons, circles, oriented rectangles and masks (a PNG placed at the first point) outline
  an object: its mask ("given") and the box around it; a rectangle is a box alone (the
  pipeline cuts its mask);
- lines, line strips and points outline nothing: they are left out with a note, as are the
  regions LabelMe reserves (`__ignore__`, `_background_`);
- labels become NYU-40 classes as COCO's category names do; a file without shapes gives no
  boxes, so the pipeline's detector looks for objects.
"""

from __future__ import annotations

import base64
import binascii
import io
import math
from dataclasses import dataclass
from pathlib import Path, PurePosixPath
from typing import Any

import numpy as np
from PIL import Image, ImageDraw, UnidentifiedImageError

from ...pipeline.base import Detection
from ..validation import InputError, InputFiles, Photo, load_photo
from .items import (
    DatasetItem,
    class_map_beside,
    labelled_detection,
    load_json,
    named_file,
    polygon_pixels,
)

RESERVED_LABELS = frozenset({"__ignore__", "_background_"})
NOT_OUTLINES = frozenset({"line", "linestrip", "point", "points"})


def is_labelme(data: Any) -> bool:
    return (
        isinstance(data, dict) and "shapes" in data and ("imagePath" in data or "imageData" in data)
    )


def read_labelme(path: Path) -> DatasetItem:
    """The photo and objects of one LabelMe file, or why it does not read."""
    try:
        data = load_json(path)
        if not is_labelme(data):
            raise InputError(f"{path.name} is not a LabelMe file (no shapes and imagePath)")
        photo = _photo(path, data)
        shapes = data["shapes"]
        if not isinstance(shapes, list):
            raise InputError("'shapes' must be a list")
        detections, notes = _objects(shapes, photo, class_map_beside(path))
    except InputError as exc:
        return DatasetItem(name=str(path), error=str(exc))
    inputs = InputFiles(
        photo=photo, K=None, detections=detections if shapes else None, notes=tuple(notes)
    )
    return DatasetItem(name=str(path), inputs=inputs)


def _photo(path: Path, data: dict[str, Any]) -> Photo:
    """The photo at imagePath when it is there and reads (the original bytes), else
    imageData; a Windows path is read as one, and a file beside the JSON of that name too."""
    image_path = data.get("imagePath")
    problem = "is missing"
    if isinstance(image_path, str) and image_path:
        relative = PurePosixPath(image_path.replace("\\", "/"))
        for candidate in (path.parent / relative, path.parent / relative.name):
            found = named_file(candidate, f"imagePath {image_path}")
            if found is not None and found.resolve() != path.resolve():
                try:
                    return load_photo(found.read_bytes())
                except InputError as exc:
                    problem = f"does not read ({exc})"
    embedded = data.get("imageData")
    if isinstance(embedded, str) and embedded:
        try:
            return load_photo(base64.b64decode(embedded, validate=True))
        except (binascii.Error, ValueError) as exc:
            if isinstance(exc, InputError):
                raise
            raise InputError(f"imageData is not base64: {exc}") from exc
    raise InputError(f"the image file {image_path} {problem} and the file embeds no imageData")


@dataclass
class _Object:
    where: str
    label: Any
    boxes: list[list[float]]  # of the parts without a mask (rectangles)
    pixels: np.ndarray | None  # the union of the parts' masks


def _objects(
    shapes: list[Any], photo: Photo, class_map: dict[str, str] | None
) -> tuple[list[Detection], list[str]]:
    """The objects of the shapes (one per label and group, in the order of their first
    shape), and notes on the shapes left out."""
    objects: dict[Any, _Object] = {}
    notes: list[str] = []
    for index, shape in enumerate(shapes):
        where = f"shape {index}"
        if not isinstance(shape, dict) or not isinstance(shape.get("points"), list):
            raise InputError(f"{where} must be an object with 'label' and 'points'")
        label, kind = shape.get("label"), shape.get("shape_type") or "polygon"
        if label in RESERVED_LABELS:
            continue  # LabelMe's regions to ignore and its background: no objects
        if kind in NOT_OUTLINES:
            notes.append(f"{where} ({label}): a {kind} outlines no object; left out")
            continue
        group = shape.get("group_id")
        key = (repr(label), repr(group)) if group is not None else index
        obj = objects.setdefault(key, _Object(where, label, [], None))
        box, pixels = _part(where, kind, shape, photo)
        if box is not None:
            obj.boxes.append(box)
        if pixels is not None:
            obj.pixels = pixels if obj.pixels is None else obj.pixels | pixels
    detections = []
    for obj in objects.values():
        box = None
        if obj.boxes:  # a rectangle among the parts: the box holds them all
            outlines = [*obj.boxes, *([_bounds(obj.pixels)] if obj.pixels is not None else [])]
            box = [min(b[0] for b in outlines), min(b[1] for b in outlines)]
            box += [max(b[2] for b in outlines), max(b[3] for b in outlines)]
        detections.append(
            labelled_detection(
                obj.where, obj.label, box, obj.pixels, photo.width, photo.height, class_map
            )
        )
    return detections, notes


def _part(
    where: str, kind: str, shape: dict[str, Any], photo: Photo
) -> tuple[list[float] | None, np.ndarray | None]:
    """(box, None) of a rectangle, (None, mask) of any other outline."""
    points = shape["points"]
    if not all(isinstance(p, list) and len(p) == 2 for p in points):
        raise InputError(f"{where}: 'points' must be [x, y] pairs")
    flat = [v for point in points for v in point]
    if not all(isinstance(v, int | float) and not isinstance(v, bool) for v in flat):
        raise InputError(f"{where}: 'points' must be numbers")
    size = photo.width, photo.height
    if kind in ("rectangle", "circle", "mask") and len(points) != 2:
        raise InputError(f"{where}: a {kind} has 2 points, it has {len(points)}")
    if kind == "rectangle":
        xs, ys = flat[::2], flat[1::2]
        return [float(min(xs)), float(min(ys)), float(max(xs)), float(max(ys))], None
    if kind in ("polygon", "oriented_rectangle"):
        return None, polygon_pixels(where, flat, *size)
    if kind == "circle":
        (cx, cy), (px, py) = points
        return None, _disc(float(cx), float(cy), math.hypot(px - cx, py - cy), size)
    if kind == "mask":
        return None, _placed_mask(where, shape.get("mask"), points[0], size)
    raise InputError(
        f"{where}: shape_type {kind!r} is not read (polygon, rectangle, circle, "
        "oriented_rectangle, mask; lines and points are left out)"
    )


def _disc(cx: float, cy: float, radius: float, size: tuple[int, int]) -> np.ndarray:
    canvas = Image.new("1", size, 0)
    ImageDraw.Draw(canvas).ellipse((cx - radius, cy - radius, cx + radius, cy + radius), fill=1)
    return np.asarray(canvas, dtype=bool)


def _placed_mask(
    where: str, encoded: Any, corner: list[float], size: tuple[int, int]
) -> np.ndarray:
    """A mask shape's PNG (base64) put into the photo with its top-left at `corner`."""
    if not isinstance(encoded, str) or not encoded:
        raise InputError(f"{where}: a mask shape needs its 'mask' (a base64 PNG)")
    try:
        with Image.open(io.BytesIO(base64.b64decode(encoded, validate=True))) as image:
            patch = np.asarray(image.convert("L")) > 0
    except (binascii.Error, ValueError, UnidentifiedImageError, OSError) as exc:
        raise InputError(f"{where}: its mask is not a base64 PNG ({exc})") from exc
    width, height = size
    x0, y0 = round(corner[0]), round(corner[1])
    out = np.zeros((height, width), dtype=bool)
    top, left = max(y0, 0), max(x0, 0)
    bottom, right = min(y0 + patch.shape[0], height), min(x0 + patch.shape[1], width)
    if top < bottom and left < right:
        out[top:bottom, left:right] = patch[top - y0 : bottom - y0, left - x0 : right - x0]
    return out


def _bounds(pixels: np.ndarray) -> list[float]:
    rows, cols = np.nonzero(pixels)
    if not len(rows):
        return [0.0, 0.0, 0.0, 0.0]
    return [float(cols.min()), float(rows.min()), float(cols.max() + 1), float(rows.max() + 1)]
