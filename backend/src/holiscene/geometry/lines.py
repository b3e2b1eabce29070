"""Line segments from a photo (OpenCV's LSD) in homogeneous form."""

from __future__ import annotations

from dataclasses import dataclass

import cv2
import numpy as np

from .camera import FloatArray


@dataclass(frozen=True)
class Segments:
    """N segments: endpoints (N, 4) as x1, y1, x2, y2 in pixels of the original image."""

    endpoints: FloatArray

    @property
    def lengths(self) -> FloatArray:
        d = self.endpoints[:, 2:] - self.endpoints[:, :2]
        result: FloatArray = np.hypot(d[:, 0], d[:, 1])
        return result

    @property
    def midpoints(self) -> FloatArray:
        result: FloatArray = (self.endpoints[:, :2] + self.endpoints[:, 2:]) / 2.0
        return result

    @property
    def directions(self) -> FloatArray:
        d = self.endpoints[:, 2:] - self.endpoints[:, :2]
        result: FloatArray = d / np.maximum(self.lengths[:, None], 1e-9)
        return result

    def homogeneous_lines(self) -> FloatArray:
        """Unit-normalised lines l with l . (x, y, 1) = 0 for points on the segment."""
        ones = np.ones((len(self.endpoints), 1))
        p = np.hstack([self.endpoints[:, :2], ones])
        q = np.hstack([self.endpoints[:, 2:], ones])
        lines = np.cross(p, q)
        result: FloatArray = lines / np.maximum(
            np.linalg.norm(lines[:, :2], axis=1, keepdims=True), 1e-9
        )
        return result

    def subset(self, keep: np.ndarray) -> Segments:
        return Segments(self.endpoints[keep])


def detect_segments(
    rgb: np.ndarray, max_side: int = 800, min_length_frac: float = 0.025
) -> Segments:
    """LSD segments longer than `min_length_frac` of the image diagonal.

    Large photos are downscaled first (LSD's cost grows with pixels, its accuracy does not).
    """
    gray = cv2.cvtColor(rgb, cv2.COLOR_RGB2GRAY)
    h, w = gray.shape
    scale = min(1.0, max_side / max(h, w))
    if scale < 1.0:
        gray = cv2.resize(gray, (round(w * scale), round(h * scale)), interpolation=cv2.INTER_AREA)
    detector = cv2.createLineSegmentDetector()
    found = detector.detect(gray)[0]
    if found is None:
        return Segments(np.zeros((0, 4)))
    # OpenCV 5 returns (N, 4), 4.x returns (N, 1, 4).
    endpoints = np.asarray(found, dtype=float).reshape(-1, 4) / scale
    segments = Segments(endpoints)
    return segments.subset(segments.lengths >= min_length_frac * float(np.hypot(h, w)))
