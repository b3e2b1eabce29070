"""Depth given with a photo (an RGB-D camera's): checked, in metres, and kept as the 16-bit
PNG of millimetres a scene's folder holds (depth.png, `DepthRef` in the scene).

Depth is along the optical axis, pixel for pixel with the photo; 0 means the sensor saw
nothing there. Every refusal is an InputError that names the problem, raised before anything
is stored.
"""

from __future__ import annotations

import hashlib
import io
from dataclasses import dataclass
from functools import cached_property
from typing import Literal, get_args

import cv2
import numpy as np
from holiscene_schema import DepthRef

from .errors import InputError

DEPTH_FILE = "depth.png"
METRES_PER_UNIT = 0.001  # depth.png holds millimetres
MAX_DEPTH_M = 65.535  # what 16-bit millimetres can hold
# Less than this share of pixels with depth is no depth image worth using.
MIN_VALID_SHARE = 0.05
PNG_SIGNATURE = b"\x89PNG\r\n\x1a\n"
NPY_MAGIC = b"\x93NUMPY"
# How an uploaded depth file's values are read: a 16-bit PNG of millimetres ("mm"), the same
# with SUN RGB-D's rotated bits ("sunrgbd"), or a NumPy .npy of float metres ("m").
DepthUnits = Literal["mm", "sunrgbd", "m"]
DEPTH_UNITS: tuple[DepthUnits, ...] = get_args(DepthUnits)
# A median above this many "metres" is a float file of millimetres, not of metres.
MILLIMETRES_LIKE_M = 100.0


@dataclass(frozen=True)
class DepthMap:
    metres: np.ndarray  # float32 (H, W); 0 where there is no depth

    @cached_property
    def png(self) -> bytes:
        """The 16-bit PNG of millimetres stored beside the scene."""
        millimetres = np.round(self.metres / METRES_PER_UNIT).astype(np.uint16)
        ok, encoded = cv2.imencode(".png", millimetres)
        if not ok:
            raise InputError("the depth image could not be encoded as PNG")
        return bytes(encoded.tobytes())

    @cached_property
    def digest(self) -> str:
        return hashlib.sha256(self.png).hexdigest()

    @staticmethod
    def ref() -> DepthRef:
        return DepthRef(file=DEPTH_FILE, metres_per_unit=METRES_PER_UNIT)


def _check_shape(shape: tuple[int, ...], width: int, height: int, what: str) -> None:
    if len(shape) != 2:
        raise InputError(f"{what} must be one channel of depth, it has shape {shape}")
    if shape != (height, width):
        raise InputError(
            f"{what} is {shape[1]}x{shape[0]} pixels, the photo is "
            f"{width}x{height}: depth must be registered to the photo, pixel for pixel"
        )


def depth_from_metres(metres: np.ndarray, width: int, height: int, what: str) -> DepthMap:
    """Depth in metres (a float array: NYU's, or decoded from a PNG); NaN, infinite,
    negative or out-of-range values count as no depth. `what` names the source in messages."""
    _check_shape(metres.shape, width, height, what)
    values = metres.astype(np.float32)
    usable = np.isfinite(values) & (values > 0) & (values < MAX_DEPTH_M)
    if not usable.any():
        raise InputError(f"{what} holds no depth (every pixel is 0, NaN or out of range)")
    if usable.mean() < MIN_VALID_SHARE:
        raise InputError(
            f"{what} has depth at only {100 * usable.mean():.1f}% of its pixels (at least "
            f"{100 * MIN_VALID_SHARE:.0f}% needed)"
        )
    return DepthMap(metres=np.where(usable, values, 0.0).astype(np.float32))


def depth_from_png(
    data: bytes,
    width: int,
    height: int,
    *,
    metres_per_unit: float = METRES_PER_UNIT,
    sunrgbd_bit_rotation: bool = False,
    what: str = DEPTH_FILE,
) -> DepthMap:
    """A 16-bit PNG of depth units (millimetres by default). SUN RGB-D stores its millimetres
    rotated by 3 bits (`sunrgbd_bit_rotation`): depth = (v >> 3) | (v << 13)."""
    if not data.startswith(PNG_SIGNATURE):
        raise InputError(
            f"{what} is not a PNG image (depth is a 16-bit PNG of millimetres, or a .npy of metres)"
        )
    if len(data) >= 24 and data[12:16] == b"IHDR":
        # The size in the header, before decoding: a file of another size (or a huge one) is
        # refused without unpacking its pixels.
        _check_shape((_be32(data[20:24]), _be32(data[16:20])), width, height, what)
    decoded = cv2.imdecode(np.frombuffer(data, np.uint8), cv2.IMREAD_UNCHANGED)
    if decoded is None:
        raise InputError(f"{what} is not a PNG image that can be decoded")
    if decoded.dtype != np.uint16:
        raise InputError(
            f"{what} is an {decoded.dtype.itemsize * 8}-bit image; depth needs 16 bits per "
            "pixel (millimetres), an 8-bit image cannot hold it"
        )
    if decoded.ndim != 2:
        raise InputError(f"{what} has {decoded.shape[2]} channels; depth needs one")
    units = np.asarray(decoded, dtype=np.uint16)
    if sunrgbd_bit_rotation:
        units = np.bitwise_or(np.right_shift(units, 3), np.left_shift(units, 13))
    return depth_from_metres(units.astype(np.float32) * metres_per_unit, width, height, what)


def _be32(raw: bytes) -> int:
    return int.from_bytes(raw, "big")


def depth_from_npy(data: bytes, width: int, height: int, what: str) -> DepthMap:
    """A NumPy .npy of float metres, (H, W); NaN or infinite values count as no depth. The
    header's shape and dtype are checked before the data is read (no pickles are loaded)."""
    stream = io.BytesIO(data)
    try:
        version = np.lib.format.read_magic(stream)
        if version == (1, 0):
            shape, _, dtype = np.lib.format.read_array_header_1_0(stream)
        elif version == (2, 0):
            shape, _, dtype = np.lib.format.read_array_header_2_0(stream)
        else:
            raise ValueError(f"version {version[0]}.{version[1]} is not read")
    except ValueError as exc:
        raise InputError(f"{what} is not a .npy file that can be read: {exc}") from exc
    if dtype.kind != "f":
        raise InputError(
            f"{what} holds {dtype} values; a .npy of depth must hold float metres "
            "(millimetres belong in a 16-bit PNG)"
        )
    _check_shape(tuple(shape), width, height, what)
    try:
        metres = np.load(io.BytesIO(data), allow_pickle=False)
    except (ValueError, OSError, EOFError) as exc:
        raise InputError(f"{what} is cut short or damaged: {exc}") from exc
    finite = metres[np.isfinite(metres) & (metres > 0)]
    if finite.size and float(np.median(finite)) > MILLIMETRES_LIKE_M:
        raise InputError(
            f"{what} has a median depth of {float(np.median(finite)):.0f} m: a .npy of depth "
            "holds metres (millimetres belong in a 16-bit PNG)"
        )
    return depth_from_metres(metres, width, height, what)


def read_depth_file(
    data: bytes, width: int, height: int, units: DepthUnits | None = None, what: str = "depth"
) -> DepthMap:
    """An uploaded depth file, told apart by its content: a 16-bit PNG read as `units` "mm"
    (the default) or "sunrgbd", or a .npy of float metres (units "m" or none)."""
    if data.startswith(NPY_MAGIC):
        if units not in (None, "m"):
            raise InputError(
                f"{what} is a .npy file (float metres); depth units {units!r} are for a 16-bit PNG"
            )
        return depth_from_npy(data, width, height, what)
    if units == "m":
        raise InputError(f"depth units 'm' are for a .npy file of float metres; {what} is not one")
    return depth_from_png(data, width, height, sunrgbd_bit_rotation=units == "sunrgbd", what=what)
