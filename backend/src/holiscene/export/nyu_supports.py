"""Stored scenes as NYU Depth v2's labelled file and support labels (`holiscene export --format
nyu-supports`), in the layout inputs.datasets.nyu reads, so importing the folder gives the
same classes, boxes, masks and supports back.

- `nyu_depth_v2_labeled.mat` (MATLAB v7.3): `images`, `labels`, `instances`, `names` and
  `scenes` (the scene names, without the image number an NYU import put in front, which
  the next import puts back); no `depths`. Each object is painted into `labels` under its
  name (its `source_class` while that still maps to its class, else the class), the larger
  objects first so a smaller one in front of a larger one keeps its pixels; an object
  without a mask is painted as its box.
- `support_labels.mat` (level 5, as the NYU file): per image, rows (supported, supporting,
  type) over the toolbox's region numbers, 0 for the floor. The wall and the ceiling are
  regions in NYU's files: a scene whose supports name them gets a `wall` region, and a
  `ceiling` region, of the pixels no object covers (the ceiling takes the upper half of them
  when both are named).
- An object the toolbox cannot number (under 10 pixels, or hidden entirely behind smaller
  objects) has no support row, nor have the objects it supports.
"""

from __future__ import annotations

import os
import re
import struct
import tempfile
from collections import Counter
from dataclasses import dataclass
from pathlib import Path

import h5py
import numpy as np
from holiscene_schema import Scene, SceneObject, map_class_name
from PIL import Image
from tqdm import tqdm

from ..core.atomic_files import write_atomic
from ..inputs.datasets.nyu import SUPPORT_FILE, SUPPORT_VARIABLE, nyu_regions
from ..segmentation.rle import decode_mask
from .archive import ArchivedScene
from .errors import ExportRefusedError
from .matfile import MatCell, mat_file

LABELLED_FILE = "nyu_depth_v2_labeled.mat"
TYPE_NUMBERS = {"below": 1, "behind": 2}
ROOM_REGIONS = ("wall", "ceiling")  # floor is supporter 0 and needs no region


@dataclass(frozen=True)
class LabelledImage:
    rgb: np.ndarray  # (H, W, 3) uint8
    labels: np.ndarray  # (H, W) uint16
    instances: np.ndarray  # (H, W) uint16
    supports: np.ndarray  # (M, 3) rows over region numbers


def export_name(obj: SceneObject) -> str:
    """The name an object is written under: the one it was imported with while that name
    still gives its class (a person may have changed the class since), else the class."""
    if obj.source_class and map_class_name(obj.source_class).cls == obj.cls:
        return obj.source_class
    return obj.cls


def write_nyu_supports(chosen: list[ArchivedScene], out: Path) -> None:
    """DIR/nyu_depth_v2_labeled.mat and DIR/support_labels.mat of the scenes (one size)."""
    sizes = {(item.scene.image.width, item.scene.image.height) for item in chosen}
    if len(sizes) > 1:
        shown = ", ".join(f"{w}x{h}" for w, h in sorted(sizes))
        raise ExportRefusedError(
            f"nyu-supports puts every image in one array, so the scenes must share one size; "
            f"they have {shown} (export each size with --scene)"
        )
    rows = _write_labelled(out / LABELLED_FILE, chosen)
    # An (N, 1) cell of (M, 3) double matrices, as NYU's file has it.
    cell = MatCell(rows, column=True)
    write_atomic(out / SUPPORT_FILE, mat_file({SUPPORT_VARIABLE: cell}, "holiscene export"))


def _labelled_image(item: ArchivedScene, names: dict[str, int]) -> LabelledImage:
    scene = item.scene
    width, height = scene.image.width, scene.image.height
    rgb = np.asarray(Image.open(item.photo).convert("RGB"))
    labels = np.zeros((height, width), dtype=np.uint16)
    instances = np.zeros((height, width), dtype=np.uint16)
    pairs: dict[str, tuple[int, int]] = {}  # object id or room name -> (label, instance)
    counts: dict[int, int] = {}
    painted = [(obj.id, export_name(obj), _pixels(obj, width, height)) for obj in scene.objects]
    for key, name, _ in painted:
        label = names.setdefault(name, len(names) + 1)
        counts[label] = counts.get(label, 0) + 1
        pairs[key] = (label, counts[label])
    for key, _, pixels in sorted(painted, key=lambda p: -int(p[2].sum())):
        labels[pixels], instances[pixels] = pairs[key]
    for room, pixels in _room_pixels(scene, labels == 0).items():
        label = names.setdefault(room, len(names) + 1)
        counts[label] = counts.get(label, 0) + 1
        pairs[room] = (label, counts[label])
        labels[pixels], instances[pixels] = pairs[room]
    numbers = {(r.label, r.instance): r.number for r in nyu_regions(labels, instances)}
    number = {key: numbers.get(pair) for key, pair in pairs.items()}
    rows = []
    for support in scene.supports:
        child = number.get(support.child)
        parent = 0 if support.parent == "floor" else number.get(support.parent)
        if child is not None and parent is not None:
            rows.append((child, parent, TYPE_NUMBERS[support.type]))
    return LabelledImage(rgb, labels, instances, np.array(rows, dtype=float).reshape(-1, 3))


def _pixels(obj: SceneObject, width: int, height: int) -> np.ndarray:
    if obj.mask is not None:
        return decode_mask(obj.mask, width, height)
    pixels = np.zeros((height, width), dtype=bool)
    x1, y1, x2, y2 = (round(v) for v in obj.bbox)
    pixels[max(y1, 0) : y2, max(x1, 0) : x2] = True
    return pixels


def _room_pixels(scene: Scene, free: np.ndarray) -> dict[str, np.ndarray]:
    """The wall and ceiling regions the scene's supports need, from the pixels no object
    covers: the ceiling takes the upper half of those rows when both are needed."""
    needed = [room for room in ROOM_REGIONS if any(s.parent == room for s in scene.supports)]
    if len(needed) < 2:
        return {room: free for room in needed}
    rows = np.flatnonzero(free.any(axis=1))
    middle = int(rows[len(rows) // 2]) if len(rows) else 0
    upper = np.zeros_like(free)
    upper[:middle] = True
    return {"wall": free & ~upper, "ceiling": free & upper}


def _write_labelled(path: Path, chosen: list[ArchivedScene]) -> list[np.ndarray]:
    """The labelled file as MATLAB v7.3 writes it, one image at a time (NYU's 1449 would
    take 3 GB at once), written beside `path` and renamed; each image's support rows."""
    width, height = chosen[0].scene.image.width, chosen[0].scene.image.height
    count = len(chosen)
    # NYU's instances are uint8; a scene with more than 255 of one name needs more.
    most = max(max(Counter(map(export_name, i.scene.objects)).values(), default=0) for i in chosen)
    shapes = {
        "images": ((count, 3, width, height), np.uint8),
        "labels": ((count, width, height), np.uint16),
        "instances": ((count, width, height), np.uint8 if most + 1 < 256 else np.uint16),
    }
    names: dict[str, int] = {}  # name -> label, in order of first use
    rows = []
    fd, tmp = tempfile.mkstemp(dir=path.parent, prefix=f".{path.name}.")
    os.close(fd)
    try:
        with h5py.File(tmp, "w", userblock_size=512) as file:
            arrays = {}
            for key, (shape, dtype) in shapes.items():
                arrays[key] = file.create_dataset(
                    key, shape, dtype=dtype, chunks=(1, *shape[1:]), compression="gzip"
                )
                arrays[key].attrs["MATLAB_class"] = np.bytes_(np.dtype(dtype).name)
            for index, item in enumerate(tqdm(chosen, "nyu-supports", unit="scene", disable=None)):
                image = _labelled_image(item, names)
                arrays["images"][index] = image.rgb.transpose(2, 1, 0)
                arrays["labels"][index] = image.labels.T
                arrays["instances"][index] = image.instances.T
                rows.append(image.supports)
            _write_strings(file, "names", list(names))
            scenes = [re.sub(r"^\d{4,}_", "", item.scene.name) for item in chosen]
            _write_strings(file, "scenes", scenes)
        with open(tmp, "r+b") as raw:
            raw.write(_v73_header())
        os.chmod(tmp, 0o644)
        os.replace(tmp, path)
    finally:
        if os.path.exists(tmp):
            os.unlink(tmp)
    return rows


def _write_strings(file: h5py.File, key: str, texts: list[str]) -> None:
    """A (1, n) cell of char arrays: references to uint16 codes kept in #refs#."""
    refs = file.require_group("#refs#")
    references = []
    for index, text in enumerate(texts):
        codes = np.array([[ord(c)] for c in text], dtype=np.uint16).reshape(-1, 1)
        target = refs.create_dataset(f"{key}_{index}", data=codes)
        target.attrs["MATLAB_class"] = np.bytes_("char")
        target.attrs["MATLAB_int_decode"] = np.int32(2)
        references.append(target.ref)
    cell = file.create_dataset(key, (1, len(texts)), dtype=h5py.ref_dtype)
    cell[0, :] = references
    cell.attrs["MATLAB_class"] = np.bytes_("cell")


def _v73_header() -> bytes:
    """The 128 bytes MATLAB puts in front of a v7.3 file's HDF5 data."""
    text = b"MATLAB 7.3 MAT-file, Platform: holiscene export, HDF5 schema 1.00 ."
    return text.ljust(116, b" ") + b"\0" * 8 + struct.pack("<H", 0x0200) + b"IM"
