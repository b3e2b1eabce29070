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


def depth_preview_png(stored_png: bytes) -> bytes:
    """An 8-bit RGBA PNG of the same size as the depth (and so the photo)."""
    depth = cv2.imdecode(np.frombuffer(stored_png, np.uint8), cv2.IMREAD_UNCHANGED)
    if depth is None or depth.ndim != 2:
        raise ValueError("the stored depth is not a one-channel PNG")
    present = depth > 0
    values = depth[present].astype(np.float32)
    near, far = (
        np.percentile(values, [LOW_PERCENTILE, HIGH_PERCENTILE]) if values.size else (0.0, 1.0)
    )
    nearness = 1.0 - np.clip((depth.astype(np.float32) - near) / max(far - near, 1.0), 0.0, 1.0)
    colours = cv2.applyColorMap(np.round(nearness * 255).astype(np.uint8), cv2.COLORMAP_TURBO)
    alpha = np.where(present, 255, 0).astype(np.uint8)
    ok, encoded = cv2.imencode(".png", np.dstack([colours, alpha]))
    if not ok:
        raise ValueError("the depth preview could not be encoded as PNG")
    return bytes(encoded.tobytes())
