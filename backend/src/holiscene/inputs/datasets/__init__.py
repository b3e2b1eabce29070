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
from .nyu import is_nyu_file, nyu_files, read_nyu
from .sunrgbd import is_sunrgbd, read_sunrgbd

__all__ = ["DatasetItem", "dataset_items", "is_dataset", "read_coco", "read_labelme"]

# A folder holding one of these is a COCO dataset.
COCO_FILE_PATTERNS = ("annotations.json", "instances*.json")
# JSON files of an input folder, never a LabelMe file.
INPUT_FOLDER_FILES = ("detections.json", "class_map.json")
PHOTO_NAMES = ("img.jpg", "img.jpeg", "img.png")
ARCHIVE_INDEX = "index.json"


def _coco_files(folder: Path) -> list[Path]:
    return sorted(
        {f for pattern in COCO_FILE_PATTERNS for f in folder.glob(pattern) if f.is_file()}
    )


def _labelme_candidates(folder: Path) -> list[Path]:
    return sorted(
        f
        for f in folder.glob("*.json")
        if f.is_file() and f.name not in INPUT_FOLDER_FILES and not is_archive_index(f)
    )


def is_archive_index(path: Path) -> bool:
    """Whether `path` is the list of folders of the app's "Download selected" zip
    (export/archive.py: index.json, {"scenes": [{"folder": ...}, ...]}), which sits beside
    input folders and is no LabelMe file."""
    if path.name != ARCHIVE_INDEX:
        return False
    try:
        data = load_json(path)
    except InputError:
        return False
    scenes = data.get("scenes") if isinstance(data, dict) else None
    return isinstance(scenes, list) and all(isinstance(s, dict) and "folder" in s for s in scenes)


def is_dataset(path: Path) -> bool:
    """Whether `path` is a dataset file or folder rather than an input folder: a .json or an
    NYU .mat file, or a folder with an NYU .mat, a COCO file or other JSON files (LabelMe's)
    and no img.jpg/img.png."""
    if (path.suffix.lower() == ".json" or is_nyu_file(path)) and not path.is_dir():
        return True
    if not path.is_dir() or any((path / n).is_file() for n in PHOTO_NAMES):
        return False
    if nyu_files(path):  # NYU Depth v2's labelled .mat (support_labels.mat beside it)
        return True
    return bool(_coco_files(path) or _labelme_candidates(path) or is_sunrgbd(path))


def dataset_items(path: Path) -> Iterator[DatasetItem]:
    """The photos of a dataset file or folder, the format told by the content."""
    if path.is_dir():
        files = nyu_files(path) or _coco_files(path) or _labelme_candidates(path)
        if not files and is_sunrgbd(path):  # SUN RGB-D image folders at any depth
            yield from read_sunrgbd(path)
            return
        if not files:
            yield DatasetItem(name=str(path), error="holds no COCO or LabelMe files")
        for file in files:
            yield from dataset_items(file)
        return
    if is_nyu_file(path):
        yield from read_nyu(path)
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
