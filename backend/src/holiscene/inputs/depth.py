"""Depth given with a photo (an RGB-D camera's): checked, in metres, and kept as the 16-bit
PNG of millimetres a scene's folder holds (depth.png, `DepthRef` in the scene).

Depth is along the optical axis, pixel for pixel with the photo; 0 means the sensor saw
nothing there. Every refusal is an InputError that names the problem, raised before anything
is stored.
"""

from __future__ import annotations

import hashlib
from dataclasses import dataclass
from functools import cached_property

import cv2
import numpy as np
from holiscene_schema import DepthRef

from .errors import InputError

DEPTH_FILE = "depth.png"
METRES_PER_UNIT = 0.001  # depth.png holds millimetres
MAX_DEPTH_M = 65.535  # what 16-bit millimetres can hold
# Less than this share of pixels with depth is no depth image worth using.
MIN_VALID_SHARE = 0.05


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


def depth_from_metres(metres: np.ndarray, width: int, height: int, what: str) -> DepthMap:
    """Depth in metres (a float array: NYU's, or decoded from a PNG); NaN, infinite,
    negative or out-of-range values count as no depth. `what` names the source in messages."""
    if metres.ndim != 2:
        raise InputError(f"{what} must be one channel of depth, it has shape {metres.shape}")
    if metres.shape != (height, width):
        raise InputError(
            f"{what} is {metres.shape[1]}x{metres.shape[0]} pixels, the photo is "
            f"{width}x{height}: depth must be registered to the photo, pixel for pixel"
        )
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
    decoded = cv2.imdecode(np.frombuffer(data, np.uint8), cv2.IMREAD_UNCHANGED)
    if decoded is None:
        raise InputError(f"{what} is not a PNG image")
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
