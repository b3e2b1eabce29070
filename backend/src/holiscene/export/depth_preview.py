"""A scene's depth as a colour picture for people (the workbench lays it over the photo): the
stored 16-bit PNG of millimetres mapped through the turbo colour map, near red and far blue,
and transparent where the sensor saw nothing."""

from __future__ import annotations

import cv2
import numpy as np

# The colours span these percentiles of the depth present, so one far window or a speck of
# noise does not wash out the room.
LOW_PERCENTILE = 2.0
HIGH_PERCENTILE = 98.0


# Colours of the preview's key, sampled from near to far (CSS hex).
KEY_STOPS = 9


def _decode(stored_png: bytes) -> np.ndarray:
    depth = cv2.imdecode(np.frombuffer(stored_png, np.uint8), cv2.IMREAD_UNCHANGED)
    if depth is None or depth.ndim != 2:
        raise ValueError("the stored depth is not a one-channel PNG")
    return depth


def _span(depth: np.ndarray) -> tuple[float, float]:
    """The stored units the colours run between: near (red) and far (blue)."""
    values = depth[depth > 0].astype(np.float32)
    if not values.size:
        return 0.0, 1.0
    near, far = np.percentile(values, [LOW_PERCENTILE, HIGH_PERCENTILE])
    return float(near), max(float(far), float(near) + 1.0)


def _turbo(nearness: np.ndarray) -> np.ndarray:
    """BGR colours of nearness values in [0, 1] (1 = near)."""
    codes = np.round(np.clip(nearness, 0.0, 1.0) * 255).astype(np.uint8)
    result: np.ndarray = cv2.applyColorMap(codes, cv2.COLORMAP_TURBO)
    return result


def depth_preview_key(stored_png: bytes, metres_per_unit: float) -> tuple[float, float, list[str]]:
    """The preview's key: the near and far depths (metres) its colours span, and the colours
    from near to far (CSS hex)."""
    near, far = _span(_decode(stored_png))
    stops = _turbo(np.linspace(1.0, 0.0, KEY_STOPS).reshape(-1, 1)).reshape(-1, 3)
    colours = [f"#{r:02x}{g:02x}{b:02x}" for b, g, r in stops.tolist()]
    return near * metres_per_unit, far * metres_per_unit, colours


def depth_preview_png(stored_png: bytes) -> bytes:
    """An 8-bit RGBA PNG of the same size as the depth (and so the photo)."""
    depth = _decode(stored_png)
    present = depth > 0
    near, far = _span(depth)
    colours = _turbo(1.0 - (depth.astype(np.float32) - near) / (far - near))
    alpha = np.where(present, 255, 0).astype(np.uint8)
    ok, encoded = cv2.imencode(".png", np.dstack([colours, alpha]))
    if not ok:
        raise ValueError("the depth preview could not be encoded as PNG")
    return bytes(encoded.tobytes())
