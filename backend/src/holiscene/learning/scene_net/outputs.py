"""Where each estimate sits in the networks' raw outputs, and how run time reads them (numpy).

The layout estimation network (LEN) gives one row per photo: for pitch, roll and the room's
yaw the bins' scores then their offsets, then the log of the camera's height (metres) and the
logs of the room's five other distances (camera heights, `targets.ROOM_DISTANCES`). The object
detection network (ODN) gives one row per object: the projected centre's offset, the log
distance's bins (scores, offsets), the log size over the class's typical size, and the yaw's
bins (scores, offsets)."""

from __future__ import annotations

import math

import numpy as np
from numpy.typing import NDArray

from .bins import LOG_DISTANCE_BINS, OBJECT_YAW_BINS, PITCH_BINS, ROLL_BINS, ROOM_YAW_BINS, Bins
from .targets import ROOM_DISTANCES, ObjectTargets, RoomTargets

FloatArray = NDArray[np.float64]


def _layout(parts: list[tuple[str, int]]) -> dict[str, slice]:
    out, start = {}, 0
    for name, width in parts:
        out[name] = slice(start, start + width)
        start += width
    return out


def _binned(name: str, bins: Bins) -> list[tuple[str, int]]:
    return [(f"{name}_scores", bins.count), (f"{name}_offsets", bins.count)]


ROOM_SLICES = _layout(
    [
        *_binned("pitch", PITCH_BINS),
        *_binned("roll", ROLL_BINS),
        *_binned("yaw", ROOM_YAW_BINS),
        ("log_height", 1),
        ("log_distances", len(ROOM_DISTANCES)),
    ]
)
ROOM_OUTPUTS = max(s.stop for s in ROOM_SLICES.values())
OBJECT_SLICES = _layout(
    [
        ("centre_offset", 2),
        *_binned("distance", LOG_DISTANCE_BINS),
        ("log_size", 3),
        *_binned("yaw", OBJECT_YAW_BINS),
    ]
)
OBJECT_OUTPUTS = max(s.stop for s in OBJECT_SLICES.values())


def _decode(row: FloatArray, slices: dict[str, slice], name: str, bins: Bins) -> FloatArray:
    return bins.decode(row[..., slices[f"{name}_scores"]], row[..., slices[f"{name}_offsets"]])


def room_estimate(row: FloatArray) -> RoomTargets:
    """The LEN's output row (ROOM_OUTPUTS,) as a camera and room."""
    row = np.asarray(row, dtype=float)
    return RoomTargets(
        pitch_deg=float(_decode(row, ROOM_SLICES, "pitch", PITCH_BINS)),
        roll_deg=float(_decode(row, ROOM_SLICES, "roll", ROLL_BINS)),
        yaw_deg=float(np.clip(_decode(row, ROOM_SLICES, "yaw", ROOM_YAW_BINS), -45.0, 45.0)),
        camera_height_m=math.exp(float(row[ROOM_SLICES["log_height"]][0])),
        distances=np.exp(row[ROOM_SLICES["log_distances"]]),
    )


def object_estimates(rows: FloatArray) -> list[ObjectTargets]:
    """The ODN's output rows (n, OBJECT_OUTPUTS) as object targets."""
    rows = np.asarray(rows, dtype=float).reshape(-1, OBJECT_OUTPUTS)
    distances = _decode(rows, OBJECT_SLICES, "distance", LOG_DISTANCE_BINS)
    yaws = _decode(rows, OBJECT_SLICES, "yaw", OBJECT_YAW_BINS)
    return [
        ObjectTargets(
            centre_offset=row[OBJECT_SLICES["centre_offset"]],
            log_distance=float(distance),
            log_size=row[OBJECT_SLICES["log_size"]],
            yaw_deg=float(yaw),
        )
        for row, distance, yaw in zip(rows, distances, yaws, strict=True)
    ]
