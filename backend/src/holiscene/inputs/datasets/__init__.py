"""Labelled datasets as scenes: COCO instance files and LabelMe files, each read into one
item per photo (inputs.InputFiles with boxes and masks, or that item's error), and where
a path given to `holiscene import` points to one."""

from __future__ import annotations

from collections.abc import Iterator
from pathlib import Path

from ..validation import InputError
from .coco import is_coco, read_coco
from .items import DatasetItem, load_json
from .labelme import is_labelme, read_labelme

__all__ = ["DatasetItem", "dataset_items", "is_dataset", "read_coco", "read_labelme"]

# A folder holding one of these is a COCO dataset.
COCO_FILE_PATTERNS = ("annotations.json", "instances*.json")


def _coco_files(folder: Path) -> list[Path]:
    return sorted(
        {f for pattern in COCO_FILE_PATTERNS for f in folder.glob(pattern) if f.is_file()}
    )


def is_dataset(path: Path) -> bool:
    """Whether `path` is a dataset file or folder rather than an input folder: a .json file, or a
    folder with a COCO file or LabelMe files and no img.jpg/img.png of its own."""
    if path.is_file():
        return path.suffix.lower() == ".json"
    if not path.is_dir() or any((path / n).is_file() for n in ("img.jpg", "img.jpeg", "img.png")):
        return False
    return bool(_coco_files(path)) or any(path.glob("*.json"))


def dataset_items(path: Path) -> Iterator[DatasetItem]:
    """The photos of a dataset file or folder, the format told by the content."""
    if path.is_dir():
        coco = _coco_files(path)
        files = coco or sorted(f for f in path.glob("*.json") if f.name != "class_map.json")
        for file in files:
            yield from dataset_items(file)
        return
    try:
        data = load_json(path)
    except InputError as exc:
        yield DatasetItem(name=str(path), error=str(exc))
        return
    if is_coco(data):
        yield from read_coco(path)
    elif is_labelme(data):
        yield read_labelme(path)
    else:
        yield DatasetItem(name=str(path), error="neither a COCO instances file nor a LabelMe file")
