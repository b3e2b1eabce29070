"""LabelMe files: one JSON per photo, `shapes` of {label, points, shape_type} (polygon or
rectangle), the photo at `imagePath` (relative to the JSON) or embedded as `imageData`
(base64). Polygons become boxes with their masks ("given"); a rectangle is a box alone (the
pipeline cuts its mask); labels become NYU-40 classes as COCO's category names do."""

from __future__ import annotations

import base64
import binascii
from pathlib import Path
from typing import Any

from ...pipeline.base import Detection
from ..validation import InputError, InputFiles, Photo, load_photo
from .items import DatasetItem, class_map_beside, labelled_detection, load_json, polygon_pixels


def is_labelme(data: Any) -> bool:
    return (
        isinstance(data, dict) and "shapes" in data and ("imagePath" in data or "imageData" in data)
    )


def read_labelme(path: Path) -> DatasetItem:
    """The photo and shapes of one LabelMe file, or why it does not read."""
    try:
        data = load_json(path)
        if not is_labelme(data):
            raise InputError(f"{path.name} is not a LabelMe file (no shapes and imagePath)")
        photo = _photo(path, data)
        class_map = class_map_beside(path)
        shapes = data["shapes"]
        if not isinstance(shapes, list):
            raise InputError("'shapes' must be a list")
        detections = [
            _detection(f"shape {index}", shape, photo, class_map)
            for index, shape in enumerate(shapes)
        ]
    except InputError as exc:
        return DatasetItem(name=str(path), error=str(exc))
    return DatasetItem(
        name=str(path), inputs=InputFiles(photo=photo, K=None, detections=detections)
    )


def _photo(path: Path, data: dict[str, Any]) -> Photo:
    """The file at imagePath when it is there (the original bytes), else imageData."""
    image_path = data.get("imagePath")
    if isinstance(image_path, str) and image_path and (path.parent / image_path).is_file():
        return load_photo((path.parent / image_path).read_bytes())
    embedded = data.get("imageData")
    if isinstance(embedded, str) and embedded:
        try:
            return load_photo(base64.b64decode(embedded, validate=True))
        except (binascii.Error, ValueError) as exc:
            if isinstance(exc, InputError):
                raise
            raise InputError(f"imageData is not base64: {exc}") from exc
    raise InputError(f"the image file {image_path} is missing and the file embeds no imageData")


def _detection(where: str, shape: Any, photo: Photo, class_map: dict[str, str] | None) -> Detection:
    if not isinstance(shape, dict) or not isinstance(shape.get("points"), list):
        raise InputError(f"{where} must be an object with 'label' and 'points'")
    kind = shape.get("shape_type") or "polygon"
    points = shape["points"]
    if not all(isinstance(p, list) and len(p) == 2 for p in points):
        raise InputError(f"{where}: 'points' must be [x, y] pairs")
    flat = [v for point in points for v in point]
    label = shape.get("label")
    if kind == "rectangle":
        if len(points) != 2:
            raise InputError(f"{where}: a rectangle has 2 points, it has {len(points)}")
        xs, ys = flat[::2], flat[1::2]
        if not all(isinstance(v, int | float) and not isinstance(v, bool) for v in flat):
            raise InputError(f"{where}: 'points' must be numbers")
        box = [float(min(xs)), float(min(ys)), float(max(xs)), float(max(ys))]
        return labelled_detection(where, label, box, None, photo.width, photo.height, class_map)
    if kind != "polygon":
        raise InputError(f"{where}: shape_type {kind!r} is not read (polygon or rectangle)")
    pixels = polygon_pixels(where, flat, photo.width, photo.height)
    return labelled_detection(where, label, None, pixels, photo.width, photo.height, class_map)
