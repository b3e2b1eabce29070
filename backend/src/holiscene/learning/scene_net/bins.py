"""Bins plus offsets (Total3DUnderstanding's way of regressing angles and distances): a value
is the centre of the bin a classifier picks plus an offset within it, in bin widths. Numpy;
the training's losses read `encode`, the run time `decode`."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

FloatArray = NDArray[np.float64]


@dataclass(frozen=True)
class Bins:
    low: float
    high: float
    count: int

    @property
    def width(self) -> float:
        return (self.high - self.low) / self.count

    def centres(self) -> FloatArray:
        return np.asarray(self.low + (np.arange(self.count) + 0.5) * self.width, dtype=np.float64)

    def encode(self, values: FloatArray) -> tuple[NDArray[np.int64], FloatArray]:
        """Each value's bin (values outside the range go to the end bins) and its offset from
        that bin's centre in bin widths."""
        array = np.asarray(values, dtype=np.float64)
        index = np.clip(np.floor((array - self.low) / self.width), 0, self.count - 1)
        index = index.astype(np.int64)
        offsets: FloatArray = (array - self.centres()[index]) / self.width
        return index, offsets

    def decode(self, logits: FloatArray, offsets: FloatArray) -> FloatArray:
        """(..., count) scores and offsets -> the values of the best-scoring bins."""
        index = np.argmax(logits, axis=-1)
        chosen = np.take_along_axis(offsets, index[..., None], axis=-1)[..., 0]
        result: FloatArray = self.centres()[index] + chosen * self.width
        return result


# The camera and the room (LEN). Wider than the synthetic rooms' own ranges (pitch 0-30 deg
# down, roll within 10 deg): people hold cameras in more ways.
PITCH_BINS = Bins(-20.0, 40.0, 6)
ROLL_BINS = Bins(-20.0, 20.0, 4)
ROOM_YAW_BINS = Bins(-45.0, 45.0, 6)
# Each object (ODN): the log of its centre's distance (0.5 to 16 m), its yaw against the ray.
LOG_DISTANCE_BINS = Bins(float(np.log(0.5)), float(np.log(16.0)), 6)
OBJECT_YAW_BINS = Bins(-180.0, 180.0, 8)
