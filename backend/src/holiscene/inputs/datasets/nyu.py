"""NYU Depth v2's labelled file (`nyu_depth_v2_labeled.mat`, MATLAB v7.3, read with h5py)
and its support labels (`support_labels.mat`, Silberman et al., ECCV 2012), one item per image.

The labelled file, as h5py sees it (MATLAB's arrays transposed): `images` (N, 3, W, H) uint8,
`labels` (N, W, H) indices into `names` (1-based, 0 unlabelled), `instances` (N, W, H) the
instance number within a label, `names` (1, C) references to char arrays, and optionally
`scenes` (1, N) references to the scene names and `depths` (N, W, H) float metres along the
optical axis (registered to the photos, holes filled by NYU's toolbox).

An object is one (label, instance) pair with label > 0: its mask those pixels, its box the
mask's, its class the name through NYU's classMapping40.mat when it is beside the file,
else the lenient vocabulary (a class_map.json beside the file first, over both). Regions
whose name maps to wall, floor or ceiling are the room, not objects: a support on one names
the structural parent.

The support labels are a cell array `supportLabels`, one (M, 3) matrix per image: rows of
(supported region, supporting region, type), type 1 support from below, 2 from behind, a
supporting region of 0 (or -1, a floor hidden from view in the labelling tool) the floor.
Regions are numbered as the NYU toolbox numbers them (get_instance_masks and
run_extract_regions_from_labels): the (label, instance) pairs present in the image, pair
(0, 0) left out, sorted by label then instance; pairs covering fewer than 10 pixels are
dropped and the rest numbered 1, 2, ... in that order.
"""

from __future__ import annotations

import io
import re
from collections.abc import Iterator
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np
from holiscene_schema import (
    NYU40_CLASSES,
    STRUCTURAL_CLASSES,
    Camera,
    ImageInfo,
    Scene,
    SupportRelation,
    class_key,
    map_class_name,
    support_graph_problems,
)
from PIL import Image

from ...pipeline.base import Detection
from ...pipeline.stages.detections import objects_from_detections
from ..depth import depth_from_metres
from ..validation import InputError, InputFiles, Photo, load_photo
from .items import DatasetItem, class_map_beside, labelled_detection
from .matlab import (
    MatFileError,
    MissingVariableError,
    hdf5_string,
    read_cell_of_matrices,
    read_numeric_matrix,
    read_strings,
)

SUPPORT_FILE = "support_labels.mat"
# NYU's published mapping of its 894 names to the 40 classes (Gupta et al., CVPR 2013):
# `mapClass`, 1 x 894, the NYU-40 number (1-40, in NYU40_CLASSES's order) of each name.
CLASS_MAPPING_FILE = "classMapping40.mat"
SUPPORT_VARIABLE = "supportLabels"
LABELLED_ARRAYS = ("images", "labels", "instances", "names")
SUPPORT_AUTHOR = "NYU Depth v2"
SUPPORT_TYPES = {1: "below", 2: "behind"}
MIN_REGION_PIXELS = 10  # the toolbox drops smaller regions before numbering them
# The RGB camera's intrinsics from the NYU toolbox (camera_params.m), for its 640x480 images.
NYU_SIZE = (640, 480)
NYU_FX, NYU_FY = 5.1885790117450188e02, 5.1946961112127485e02
NYU_CX, NYU_CY = 3.2558244941119034e02, 2.5373616633400465e02


def nyu_intrinsics(width: int, height: int) -> np.ndarray:
    """NYU v2's RGB K, scaled when the images are not 640x480 (exact at 640x480)."""
    sx, sy = width / NYU_SIZE[0], height / NYU_SIZE[1]
    return np.array([[NYU_FX * sx, 0.0, NYU_CX * sx], [0.0, NYU_FY * sy, NYU_CY * sy], [0, 0, 1]])


@dataclass(frozen=True)
class Region:
    """One (label, instance) pair of an image; `number` is the toolbox's region number
    (None for a region under MIN_REGION_PIXELS, which the support labels cannot name)."""

    label: int
    instance: int
    pixels: np.ndarray  # bool (H, W)
    number: int | None


def nyu_regions(labels: np.ndarray, instances: np.ndarray) -> list[Region]:
    """The regions of an image's (H, W) label and instance maps, in the toolbox's order."""
    keys = labels.astype(np.int64) * 65536 + instances.astype(np.int64)
    regions, number = [], 0
    for key in np.unique(keys):
        if key == 0:
            continue
        pixels = keys == key
        counted = int(pixels.sum()) >= MIN_REGION_PIXELS
        number += counted
        regions.append(
            Region(int(key) // 65536, int(key) % 65536, pixels, number if counted else None)
        )
    return regions


def is_nyu_file(path: Path) -> bool:
    return path.suffix.lower() == ".mat" and path.name not in (SUPPORT_FILE, CLASS_MAPPING_FILE)


def nyu40_mapping(path: Path, names: list[str]) -> dict[str, str]:
    """The labelled file's names mapped by NYU's own classMapping40.mat (keys as class_key
    makes them); empty when the file is not there. A file that does not fit the names is
    the whole import's error: its mapping would put every object in a wrong class."""
    if not path.is_file():
        return {}
    try:
        numbers = read_numeric_matrix(path, "mapClass").ravel(order="F")
        mapped_names = _mapped_names(path)
    except MatFileError as exc:
        raise InputError(f"{CLASS_MAPPING_FILE}: {exc}") from exc
    if len(numbers) != len(names):
        raise InputError(
            f"{CLASS_MAPPING_FILE} maps {len(numbers)} names, the labelled file has {len(names)}"
        )
    if mapped_names is not None:
        # A mapping made for another release of the names would class every object wrong.
        if len(mapped_names) != len(names):
            raise InputError(
                f"{CLASS_MAPPING_FILE} names {len(mapped_names)} classes, the labelled file "
                f"{len(names)}"
            )
        for number, (mapped, name) in enumerate(zip(mapped_names, names, strict=True), 1):
            if class_key(mapped) != class_key(name):
                raise InputError(
                    f"{CLASS_MAPPING_FILE} is for other names: its name {number} is "
                    f"{mapped!r}, the labelled file's {name!r}"
                )
    if not np.all((numbers >= 1) & (numbers <= len(NYU40_CLASSES)) & (numbers % 1 == 0)):
        raise InputError(f"{CLASS_MAPPING_FILE}: mapClass holds numbers outside 1-40")
    return {class_key(n): NYU40_CLASSES[int(k) - 1] for n, k in zip(names, numbers, strict=True)}


def _mapped_names(path: Path) -> list[str] | None:
    """The names classMapping40.mat maps (its `allClassName`), None when it has none."""
    try:
        return read_strings(path, "allClassName")
    except MissingVariableError:
        return None


def nyu_files(folder: Path) -> list[Path]:
    """The labelled files in a folder: its v7.3 (HDF5) .mat files. The level-5 files NYU
    puts beside them (support_labels.mat, splits.mat) are not images."""
    import h5py

    return sorted(
        f for f in folder.glob("*.mat") if f.is_file() and is_nyu_file(f) and h5py.is_hdf5(f)
    )


def read_nyu(path: Path) -> Iterator[DatasetItem]:
    """One item per image of the labelled file at `path`, with the support labels of
    support_labels.mat beside it when there is one; a file that does not read is one item
    with its error."""
    import h5py

    try:
        file = h5py.File(path, "r")
    except OSError as exc:
        yield DatasetItem(
            name=str(path),
            error=f"{path.name} is not a readable MATLAB v7.3 (HDF5) file (truncated?): {exc}",
        )
        return
    with file:
        try:
            dataset = _NyuFile(path, file)
        except InputError as exc:
            yield DatasetItem(name=str(path), error=str(exc))
            return
        for index in range(dataset.count):
            name = f"{path}/{dataset.scene_stem(index)}"
            try:
                yield DatasetItem(name=name, inputs=dataset.image(index))
            except InputError as exc:
                yield DatasetItem(name=name, error=str(exc))


class _NyuFile:
    """The open labelled file, checked, with its names and support labels read."""

    def __init__(self, path: Path, file: Any) -> None:
        missing = [key for key in LABELLED_ARRAYS if key not in file]
        if missing:
            raise InputError(f"{path.name} is not NYU's labelled file: no {', '.join(missing)}")
        self.file = file
        self.images, self.labels, self.instances = (file[k] for k in LABELLED_ARRAYS[:3])
        if self.images.ndim != 4 or self.images.shape[1] != 3:
            raise InputError(f"images is {self.images.shape}, not (N, 3, W, H)")
        self.count = int(self.images.shape[0])
        self.depths = file.get("depths")
        for key in ("labels", "instances", "depths"):
            if key in file and file[key].shape != (self.count, *self.images.shape[2:]):
                raise InputError(
                    f"{key} is {file[key].shape}, images {self.images.shape}: they differ"
                )
        self.names = self._strings("names")
        self.scenes = self._strings("scenes") if "scenes" in file else None
        if self.scenes is not None and len(self.scenes) != self.count:
            raise InputError(f"scenes has {len(self.scenes)} names for {self.count} images")
        # The dataset's own 894 -> 40 mapping when it is beside the file, a user's class map
        # over it, and the lenient vocabulary for names neither knows.
        self.class_map = {
            **nyu40_mapping(path.parent / CLASS_MAPPING_FILE, self.names),
            **(class_map_beside(path) or {}),
        }
        self.supports = _support_rows(path.parent / SUPPORT_FILE, self.count)

    def _strings(self, key: str) -> list[str]:
        strings = []
        for number, reference in enumerate(np.asarray(self.file[key]).ravel(order="F"), 1):
            try:
                strings.append(hdf5_string(self.file, reference))
            except MatFileError as exc:
                raise InputError(f"{key} entry {number}: {exc}") from exc
        return strings

    def scene_stem(self, index: int) -> str:
        """The scene's name: the image's number (from 1, as MATLAB counts) and its scene."""
        stem = f"{index + 1:04d}"
        if self.scenes is not None:
            stem += "_" + re.sub(r"[^A-Za-z0-9_-]+", "_", self.scenes[index]).strip("_")
        return stem

    def image(self, index: int) -> InputFiles:
        try:
            rgb = np.asarray(self.images[index]).transpose(2, 1, 0)
            labels = np.asarray(self.labels[index]).T
            instances = np.asarray(self.instances[index]).T
            metres = np.asarray(self.depths[index]).T if self.depths is not None else None
        except (OSError, KeyError, ValueError) as exc:
            raise InputError(
                f"image {index + 1}'s arrays cannot be read (corrupt or truncated): {exc}"
            ) from exc
        photo = _png_photo(rgb)
        depth = (
            depth_from_metres(metres, photo.width, photo.height, f"image {index + 1}'s depth map")
            if metres is not None
            else None
        )
        regions = nyu_regions(labels, instances)
        classes = {r.label: self._class(r.label) for r in regions if r.label > 0}
        objects = [r for r in regions if r.label > 0 and classes[r.label] not in STRUCTURAL_CLASSES]
        detections = [self._detection(r, photo) for r in objects]
        ids = {(r.label, r.instance): f"o{i}" for i, r in enumerate(objects)}
        rows = self.supports[index] if self.supports is not None else np.zeros((0, 3))
        supports, notes = _supports(rows, regions, ids, classes)
        K = nyu_intrinsics(photo.width, photo.height)
        truth = Scene(
            name=self.scene_stem(index),
            image=ImageInfo(file=f"img{photo.suffix}", width=photo.width, height=photo.height),
            camera=Camera(K=K.tolist(), K_source="given", pitch_deg=None, roll_deg=None),
            objects=objects_from_detections(detections),
            supports=list(supports),
        )
        return InputFiles(
            photo=photo,
            K=K,
            detections=detections,
            supports=supports,
            ground_truth=truth,
            depth=depth,
            notes=tuple(notes),
        )

    def _class(self, label: int) -> str:
        if label > len(self.names):
            raise InputError(f"label {label} is beyond the {len(self.names)} names")
        return map_class_name(self.names[label - 1], self.class_map).cls

    def _detection(self, region: Region, photo: Photo) -> Detection:
        where = f"object {self.names[region.label - 1]!r} instance {region.instance}"
        name = self.names[region.label - 1]
        return labelled_detection(
            where, name, None, region.pixels, photo.width, photo.height, self.class_map
        )


def _png_photo(rgb: np.ndarray) -> Photo:
    buffer = io.BytesIO()
    Image.fromarray(np.ascontiguousarray(rgb, dtype=np.uint8)).save(buffer, "PNG")
    return load_photo(buffer.getvalue())


def _support_rows(path: Path, count: int) -> list[np.ndarray] | None:
    """Each image's support rows, or None without a support file."""
    if not path.is_file():
        return None
    try:
        rows = read_cell_of_matrices(path, SUPPORT_VARIABLE)
    except MatFileError as exc:
        raise InputError(str(exc)) from exc
    if len(rows) != count:
        raise InputError(f"{path.name} has support labels of {len(rows)} images, not {count}")
    for number, matrix in enumerate(rows, 1):
        if matrix.size and (matrix.ndim != 2 or matrix.shape[1] != 3):
            raise InputError(f"{path.name}: image {number}'s rows are {matrix.shape}, not (M, 3)")
    return [matrix.reshape(-1, 3) for matrix in rows]


def _supports(
    rows: np.ndarray,
    regions: list[Region],
    ids: dict[tuple[int, int], str],
    classes: dict[int, str],
) -> tuple[tuple[SupportRelation, ...], list[str]]:
    """The image's support rows as relations over the object ids, and notes on the rows left
    out. A row that names a region the image does not have refuses the image. A row of
    another type than below or behind (the labelling tool also had "hanging") is left out;
    of several supporters of one object the first from below is kept, else the first."""
    numbered = {r.number: r for r in regions if r.number is not None}

    def parent(row: int, number: int) -> str:
        if number <= 0:
            return "floor"
        region = _region(row, number, numbered)
        return ids.get((region.label, region.instance)) or classes[region.label]

    candidates: dict[str, list[tuple[int, SupportRelation]]] = {}
    notes: list[str] = []
    for row, (supported, supporter, kind) in enumerate(rows.tolist(), 1):
        region = _region(row, supported, numbered)
        child = ids.get((region.label, region.instance))
        if child is None:
            continue  # the room's own regions (a wall on the floor) are not objects
        if kind not in SUPPORT_TYPES:
            notes.append(
                f"support row {row} left out: type {kind:g} is neither 1 (below) nor 2 (behind)"
            )
            continue
        relation = SupportRelation(
            child=child,
            parent=parent(row, int(supporter)),
            type=SUPPORT_TYPES[int(kind)],
            source="manual",
            author=SUPPORT_AUTHOR,
        )
        candidates.setdefault(child, []).append((row, relation))
    relations: dict[str, SupportRelation] = {}
    for child, found in candidates.items():
        kept_row, kept = next(((r, s) for r, s in found if s.type == "below"), found[0])
        relations[child] = kept
        others = sorted({r for r, s in found if s != kept})
        if others:
            listed = ", ".join(str(r) for r in others)
            notes.append(
                f"object {child} has more than one supporter: row {kept_row} kept, "
                f"row(s) {listed} left out"
            )
    problems = support_graph_problems(
        list(ids.values()), [(r.child, r.parent) for r in relations.values()]
    )
    if problems:
        raise InputError("support labels: " + "; ".join(problems))
    return tuple(relations.values()), notes


def _region(row: int, number: float, numbered: dict[int, Region]) -> Region:
    if number != int(number) or int(number) not in numbered:
        raise InputError(
            f"support row {row} names object {number:g}, which is not there (the image has "
            f"{len(numbered)} numbered regions)"
        )
    region = numbered[int(number)]
    if region.label == 0:
        raise InputError(f"support row {row} names object {number:g}, an unlabelled region")
    return region
