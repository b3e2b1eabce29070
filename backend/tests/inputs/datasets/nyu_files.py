"""NYU Depth v2's two files, small and in their exact layout, written by the tests: the
labelled file as MATLAB v7.3 writes it (HDF5 behind a 512-byte MATLAB header, arrays
transposed, names as references to uint16 char arrays) and support_labels.mat as MATLAB's
default level-5 format writes it (each variable zlib-compressed, whole numbers stored in the
smallest integer type, short names as small elements)."""

from __future__ import annotations

import struct
import zlib
from dataclasses import dataclass, field
from pathlib import Path

import h5py
import numpy as np

WIDTH, HEIGHT = 64, 48
# Label l is NAMES[l - 1]; "teapot" is in no vocabulary (it becomes otherprop).
NAMES = ("wall", "floor", "bed", "lamp", "pillow", "teapot", "picture")


@dataclass
class NyuImage:
    rgb: np.ndarray  # (H, W, 3) uint8
    labels: np.ndarray  # (H, W) uint16
    instances: np.ndarray  # (H, W) uint8
    scene: str
    supports: list[tuple[int, int, int]] = field(default_factory=list)
    depth: np.ndarray | None = None  # (H, W) float32 metres; None: 1 m everywhere


def bedroom(seed: int = 0) -> NyuImage:
    """A wall, a floor, a bed with two pillows, a lamp, a teapot and a 9-pixel picture (too
    small for the toolbox to number). Regions: 1 wall, 2 floor, 3 bed, 4 lamp, 5 and 6 the
    pillows, 7 the teapot; objects o0 bed, o1 lamp, o2 and o3 pillows, o4 teapot, o5 picture."""
    rng = np.random.default_rng(seed)
    labels = np.zeros((HEIGHT, WIDTH), dtype=np.uint16)
    instances = np.zeros((HEIGHT, WIDTH), dtype=np.uint8)

    def paint(label: int, instance: int, rows: slice, cols: slice) -> None:
        labels[rows, cols], instances[rows, cols] = label, instance

    paint(1, 1, slice(0, 20), slice(0, WIDTH))
    paint(2, 1, slice(36, HEIGHT), slice(0, 58))  # the bottom right corner stays unlabelled
    paint(3, 1, slice(20, 36), slice(5, 41))
    paint(5, 1, slice(22, 28), slice(8, 17))
    paint(5, 2, slice(22, 28), slice(20, 29))
    paint(4, 1, slice(10, 31), slice(48, 57))
    paint(6, 1, slice(31, 35), slice(44, 48))
    paint(7, 1, slice(2, 5), slice(2, 5))
    rows = [(3, 0, 1), (4, 1, 2), (5, 3, 1), (6, 3, 1), (7, 2, 1), (1, 2, 1)]
    rgb = rng.integers(0, 255, (HEIGHT, WIDTH, 3), dtype=np.uint8)
    # Farther up the photo and to the right, so a transposed read shows.
    row, col = np.mgrid[0:HEIGHT, 0:WIDTH]
    depth = (4.0 - 0.05 * row + 0.01 * col).astype(np.float32)
    return NyuImage(rgb, labels, instances, f"bedroom_{seed:04d}", rows, depth)


def _strings(file: h5py.File, key: str, texts: list[str]) -> None:
    refs = file.require_group("#refs#")
    references: list[h5py.Reference] = []
    for text in texts:
        codes = np.array([[ord(c)] for c in text], dtype=np.uint16)
        target = refs.create_dataset(f"{key}_{len(references)}", data=codes)
        target.attrs["MATLAB_class"] = np.bytes_("char")
        target.attrs["MATLAB_int_decode"] = np.int32(2)
        references.append(target.ref)
    cell = file.create_dataset(key, (1, len(texts)), dtype=h5py.ref_dtype)
    cell[0, :] = references
    cell.attrs["MATLAB_class"] = np.bytes_("cell")


def write_labelled(
    path: Path, images: list[NyuImage], names: tuple[str, ...] = NAMES, chunked: bool = False
) -> Path:
    """The labelled file; `chunked`: each image's arrays gzip-compressed in chunks of their
    own (MATLAB compresses a v7.3 file's arrays too), so one image's can be damaged alone."""
    path.parent.mkdir(parents=True, exist_ok=True)
    storage = {"compression": "gzip"} if chunked else {}
    with h5py.File(path, "w", userblock_size=512) as file:
        arrays = {
            "images": np.stack([im.rgb.transpose(2, 1, 0) for im in images]),
            "labels": np.stack([im.labels.T for im in images]),
            "instances": np.stack([im.instances.T for im in images]),
            "depths": np.stack([_depth(im).T for im in images]),
        }
        for key, array in arrays.items():
            chunks = (1, *array.shape[1:]) if chunked else None
            dataset = file.create_dataset(key, data=array, chunks=chunks, **storage)
            dataset.attrs["MATLAB_class"] = np.bytes_(
                {"float32": "single"}.get(str(array.dtype), str(array.dtype))
            )
        _strings(file, "names", list(names))
        _strings(file, "scenes", [im.scene for im in images])
    header = b"MATLAB 7.3 MAT-file, Platform: GLNXA64, Created by the tests HDF5 schema 1.00 ."
    with path.open("r+b") as raw:
        raw.write(header.ljust(116, b" ") + b"\0" * 8 + struct.pack("<H", 0x0200) + b"IM")
    return path


def _depth(image: NyuImage) -> np.ndarray:
    if image.depth is None:
        return np.ones((HEIGHT, WIDTH), dtype=np.float32)
    return image.depth.astype(np.float32)


def _element(kind: int, payload: bytes) -> bytes:
    if len(payload) <= 4:  # a small element: count and type in one word
        return struct.pack("<I", (len(payload) << 16) | kind) + payload.ljust(4, b"\0")
    return struct.pack("<II", kind, len(payload)) + payload + b"\0" * (-len(payload) % 8)


def _matrix(name: str, mx_class: int, dims: tuple[int, ...], body: bytes) -> bytes:
    flags = struct.pack("<II", 6, 8) + struct.pack("<II", mx_class, 0)  # miUINT32, 8 bytes
    shape = struct.pack("<II", 5, 4 * len(dims)) + struct.pack(f"<{len(dims)}i", *dims)
    shape += b"\0" * (-len(shape) % 8)
    payload = flags + shape + _element(1, name.encode()) + body
    return struct.pack("<II", 14, len(payload)) + payload


def _rows(rows: list[tuple[int, int, int]]) -> bytes:
    values = np.array(rows, dtype=float).reshape(-1, 3)
    if not values.size:
        return _matrix("", 6, (0, 3), struct.pack("<II", 9, 0))
    kind, dtype = (1, "i1") if values.min() < 0 else (2, "u1")  # MATLAB's smallest type
    return _matrix("", 6, values.shape, _element(kind, values.astype(dtype).tobytes(order="F")))


def write_support_labels(path: Path, per_image: list[list[tuple[int, int, int]]]) -> Path:
    """support_labels.mat: `supportLabels`, an (N, 1) cell of (M, 3) matrices."""
    header = b"MATLAB 5.0 MAT-file, Platform: GLNXA64, Created by the tests".ljust(116, b" ")
    header += b"\0" * 8 + struct.pack("<H", 0x0100) + b"IM"
    cell = _matrix("supportLabels", 1, (len(per_image), 1), b"".join(map(_rows, per_image)))
    packed = zlib.compress(cell)
    path.write_bytes(header + struct.pack("<II", 15, len(packed)) + packed)
    return path


def nyu_folder(folder: Path, images: list[NyuImage]) -> Path:
    """folder/nyu_depth_v2_labeled.mat and folder/support_labels.mat."""
    labelled = write_labelled(folder / "nyu_depth_v2_labeled.mat", images)
    write_support_labels(folder / "support_labels.mat", [im.supports for im in images])
    return labelled
