"""Small dataset files in each format's layout, written by the tests (nothing downloaded)."""

from __future__ import annotations

import base64
import io
import json
from pathlib import Path
from typing import Any

import numpy as np
from PIL import Image

WIDTH, HEIGHT = 96, 64


def photo_bytes(
    seed: int = 0, width: int = WIDTH, height: int = HEIGHT, kind: str = "PNG"
) -> bytes:
    rng = np.random.default_rng(seed)
    buffer = io.BytesIO()
    Image.fromarray(rng.integers(0, 255, (height, width, 3), dtype=np.uint8)).save(buffer, kind)
    return buffer.getvalue()


def write_json(path: Path, data: Any) -> Path:
    path.parent.mkdir(parents=True, exist_ok=True)
    path.write_text(json.dumps(data))
    return path


def coco_file(
    folder: Path,
    annotations: list[dict[str, Any]],
    images: tuple[str, ...] = ("a.png",),
    written: tuple[str, ...] | None = None,
) -> Path:
    """annotations.json with `images` (ids from 1) in folder/images/, the ones in `written`
    (all by default) written as files."""
    for index, name in enumerate(images if written is None else written):
        (folder / "images").mkdir(parents=True, exist_ok=True)
        (folder / "images" / name).write_bytes(photo_bytes(index))
    return write_json(
        folder / "annotations.json",
        {
            "images": [
                {"id": i, "file_name": n, "width": WIDTH, "height": HEIGHT}
                for i, n in enumerate(images, start=1)
            ],
            "categories": [
                {"id": 1, "name": "couch"},
                {"id": 2, "name": "basket"},
                {"id": 3, "name": "teapot"},
            ],
            "annotations": annotations,
        },
    )


def labelme_file(path: Path, shapes: list[dict[str, Any]], embed: bool = False) -> Path:
    """A LabelMe file with its photo beside it (or embedded as imageData when `embed`)."""
    data = photo_bytes(7)
    path.parent.mkdir(parents=True, exist_ok=True)
    image_name = path.with_suffix(".png").name
    document: dict[str, Any] = {
        "version": "5.2.1",
        "flags": {},
        "shapes": shapes,
        "imagePath": image_name,
        "imageData": base64.b64encode(data).decode() if embed else None,
        "imageHeight": HEIGHT,
        "imageWidth": WIDTH,
    }
    if not embed:
        (path.parent / image_name).write_bytes(data)
    return write_json(path, document)


def shape(label: str, points: list[list[float]], kind: str = "polygon") -> dict[str, Any]:
    return {"label": label, "points": points, "group_id": None, "shape_type": kind, "flags": {}}
