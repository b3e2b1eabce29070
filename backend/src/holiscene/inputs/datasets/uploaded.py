"""Photos to import one at a time: those of a path given to `holiscene import`
(photo_sources), and what an unpacked upload holds (upload_contents): an input folder, a
COCO, LabelMe or SUN RGB-D dataset, a folder of input folders (as `holiscene export
--format scene` and the app's "Download selected" zip hold them), or plain photos (a
folder of snapshots: each a scene named after its file, without labels). The format is
told by the content, with the readers `holiscene import` uses."""

from __future__ import annotations

import dataclasses
import json
from collections.abc import Callable, Iterator
from dataclasses import dataclass
from functools import lru_cache, partial
from pathlib import Path

from ..validation import InputError, InputFiles, load_photo, read_input_folder
from . import (
    ARCHIVE_INDEX,
    PHOTO_NAMES,
    _coco_files,
    _labelme_candidates,
    dataset_items,
    is_archive_index,
    is_dataset,
)
from .coco import is_coco
from .items import DatasetItem, load_json
from .nyu import nyu_files
from .sunrgbd import image_folders, is_sunrgbd

# Left to the command line: NYU's labelled file is 2.8 GB.
NYU_REFUSAL = (
    "NYU Depth v2's labelled .mat is imported on the server with `holiscene import "
    "nyu_depth_v2_labeled.mat` (the file is 2.8 GB, too large for an upload)"
)


@dataclass(frozen=True)
class DownloadedFrom:
    """The stored scene and revision a folder of the app's download zip was written from (as
    its index.json says), and the folder's scene.json: an upload of it unchanged is no new
    scene (services/dataset_import.py, stored_before)."""

    scene_id: str
    revision: int
    scene_file: Path
    state: str | None = None  # the workflow state it had there


# A scene a reviewer had rejected carries that into the store it is imported to: its labels
# were said to be wrong (the note stays with the scene, as every import note does).
REJECTED_NOTE = "downloaded while rejected by a reviewer: its labels were said to be wrong"


@dataclass(frozen=True)
class PhotoSource:
    """One photo to import: `label` names it for the user, `name` is the scene's name, and
    `read` gives its checked inputs or raises InputError (that photo's error)."""

    label: str
    name: str
    read: Callable[[], InputFiles]
    downloaded_from: DownloadedFrom | None = None


# A photo on its own, outside an input folder: a scene without labels, named after the file.
PLAIN_PHOTO_SUFFIXES = (".jpg", ".jpeg", ".png")


def photo_sources(path: Path) -> Iterator[PhotoSource]:
    """The photos of an input folder, a dataset file or folder, a photo file or a folder of
    them, read one at a time (a dataset of a thousand photos is never in memory)."""
    if _is_plain_photo(path):
        yield PhotoSource(str(path), path.stem, partial(_read_plain_photo, path))
    elif is_dataset(path):
        for item in dataset_items(path):
            yield PhotoSource(item.name, Path(item.name).stem, partial(_item_inputs, item))
    elif path.is_dir() and not _is_input_folder(path) and (parts := _importable_parts(path)):
        # A folder of input folders (an export, the app's download zip) or of photos.
        for part in parts:
            yield from photo_sources(part)
    else:
        downloaded = _downloaded_from(path)
        yield PhotoSource(
            str(path), _folder_scene_name(path), partial(_read_folder, path, downloaded), downloaded
        )


def _is_plain_photo(path: Path) -> bool:
    return (
        path.is_file()
        and path.suffix.lower() in PLAIN_PHOTO_SUFFIXES
        and not path.name.startswith(".")
    )


def _read_plain_photo(path: Path) -> InputFiles:
    return InputFiles(photo=load_photo(path.read_bytes()), K=None, detections=None)


def _read_folder(folder: Path, downloaded: DownloadedFrom | None) -> InputFiles:
    inputs = read_input_folder(folder)
    if downloaded is not None and downloaded.state == "rejected":
        return dataclasses.replace(inputs, notes=(*inputs.notes, REJECTED_NOTE))
    return inputs


def _downloaded_from(folder: Path) -> DownloadedFrom | None:
    """Where a folder of the app's download zip came from, by the index.json beside it."""
    if not (folder / "scene.json").is_file():
        return None
    return _archive_entries(folder.parent).get(folder.name)


@lru_cache(maxsize=4)
def _archive_entries(root: Path) -> dict[str, DownloadedFrom]:
    """Folder name -> where it came from, for the download zip unpacked at `root` (empty when
    `root` holds no index.json). Read once per zip, not once per folder: an unpacked upload's
    folder has a name of its own and does not change while it is imported."""
    index = root / ARCHIVE_INDEX
    if not is_archive_index(index):
        return {}
    entries = {}
    for entry in load_json(index)["scenes"]:
        scene_id, revision, state = entry.get("scene_id"), entry.get("revision"), entry.get("state")
        if isinstance(scene_id, str) and type(revision) is int:
            shown = state if isinstance(state, str) else None
            scene_file = root / entry["folder"] / "scene.json"
            entries[entry["folder"]] = DownloadedFrom(scene_id, revision, scene_file, shown)
    return entries


def _folder_scene_name(folder: Path) -> str:
    """An input folder's scene name: the one its scene.json gives (a downloaded scene's folder
    is `<name>-<id>`), else the folder's name."""
    try:
        name = json.loads((folder / "scene.json").read_text(encoding="utf-8")).get("name")
    except (OSError, ValueError, AttributeError):
        return folder.name
    return name.strip() if isinstance(name, str) and name.strip() else folder.name


def _item_inputs(item: DatasetItem) -> InputFiles:
    if item.inputs is None:
        raise InputError(item.error or "could not be read")
    return item.inputs


@dataclass(frozen=True)
class UploadContents:
    """What an unpacked upload holds: its format for the user, how many photos, the paths
    to read them from."""

    format: str
    total: int
    paths: tuple[Path, ...]

    def sources(self) -> Iterator[PhotoSource]:
        for path in self.paths:
            yield from photo_sources(path)


def upload_contents(folder: Path) -> UploadContents:
    """Tell what the unpacked upload at `folder` holds; InputError when it is nothing
    importable. A zip of one folder is read as that folder."""
    root = folder
    while True:
        children = [c for c in root.iterdir() if not c.name.startswith(".")]
        if len(children) != 1 or not children[0].is_dir():
            break
        root = children[0]
    if any(nyu_files(d) for d in (root, *_subfolders(root))):
        raise InputError(NYU_REFUSAL)
    if _is_input_folder(root) or is_dataset(root):
        return UploadContents(_format(root), _count(root), (root,))
    parts = _importable_parts(root)
    if not parts:
        raise InputError(
            "the zip holds no COCO or LabelMe dataset, SUN RGB-D image folder, input folder "
            "(img.jpg or img.png with its files) or photo (.jpg, .png) at its top"
        )
    formats = sorted({_format(p) for p in parts})
    return UploadContents(", ".join(formats), sum(_count(p) for p in parts), tuple(parts))


def _importable_parts(root: Path) -> list[Path]:
    """The input folders and datasets directly inside `root`, then the photos lying there."""
    folders = [d for d in _subfolders(root) if _is_input_folder(d) or is_dataset(d)]
    return folders + sorted(p for p in root.iterdir() if _is_plain_photo(p))


def _subfolders(root: Path) -> list[Path]:
    return sorted(d for d in root.iterdir() if d.is_dir() and not d.name.startswith("."))


def _is_input_folder(folder: Path) -> bool:
    return any((folder / n).is_file() for n in PHOTO_NAMES)


def _format(path: Path) -> str:
    if _is_plain_photo(path):
        return "photos"
    if _is_input_folder(path):
        return "input folders"
    if _coco_files(path):
        return "COCO"
    if _labelme_candidates(path):
        return "LabelMe"
    return "SUN RGB-D" if is_sunrgbd(path) else "input folders"


def _count(path: Path) -> int:
    """How many photos (or items that will report an error) reading `path` gives; cheap:
    no photo is read."""
    if _is_plain_photo(path) or _is_input_folder(path):
        return 1
    files = _coco_files(path) or _labelme_candidates(path)
    if not files:
        return sum(1 for _ in image_folders(path)) or 1
    return sum(_photos_in_json(f) for f in files)


def _photos_in_json(path: Path) -> int:
    try:
        data = load_json(path)
    except InputError:
        return 1  # one error
    if is_coco(data) and isinstance(data["images"], list):
        return max(len(data["images"]), 1)
    return 1
