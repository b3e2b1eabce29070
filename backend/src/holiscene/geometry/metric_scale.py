"""Metric scale: the camera's height in metres, the one thing a single photo cannot give.

The room and the objects are first measured in units of the camera height. Metres come from
priors fused in log space, each weighted by how little it varies:

- the camera's height (1.4 m, sd of log 0.12: people hold cameras at chest to eye height);
- the room's height, when the ceiling's edges are seen (2.75 m, sd 0.15);
- the distance to the wall the camera faces, when it is seen (4.67 m, sd of log 0.22: people
  photograph a room from near one wall). Weak, but every photo of a room has it;
- the typical height of each floor-standing object whose bottom and top are in the photo,
  and its typical width when both its sides are in the photo;
- the typical height above the floor of the lower edge of a thing hung on a wall (a window's
  sill, a picture's lower edge), read where its ray meets the room's walls: this needs the
  room, so it joins the final scale only (`layout.mounted_heights`).

An object's height is read with the vertical through its floor contact (`ground.height_above`),
which is biased in a way that depends on the class (a box's top edge in the photo is its far
edge seen from above, its near edge seen from below; a low table is mostly top). That bias and
the measurement's real spread are learned per class on synthetic rooms with exact ground truth
(`scripts/calibrate_scale.py`, stored in `knowledge/scale_calibration.json`); a width is
read where the box's bottom edge meets the floor, and how the object is turned is left to the
same calibration. Classes with too few measurements fall back to the spread of the furniture
library's height range (heights) or are not used (widths, mountings).
"""

from __future__ import annotations

import json
import math
from collections import defaultdict
from collections.abc import Iterable, Iterator
from dataclasses import dataclass, field
from functools import lru_cache
from pathlib import Path
from typing import Literal

import numpy as np
from holiscene_schema import SceneObject
from holiscene_schema.support_geometry import TOO_LARGE_LIMITS

from ..knowledge.object_sizes import height_spread, middle_size, mounting_height
from .camera import FloatArray, PinholeCamera
from .ground import height_above, hit_horizontal_plane

CAMERA_HEIGHT_PRIOR = (1.4, 0.12)  # metres, sd of log
ROOM_HEIGHT_PRIOR = (2.75, 0.15)
# The synthetic rooms' depth (3.6-7 m) less the camera's distance from the wall behind it
# (0.25-1 m), as a log-normal. Fused with the rest, the scale's mean error went 6.4% -> 6.0%
# on 99 rooms from seed 7000 and 7.0% -> 6.2% on 149 from seed 300000 (6.3% and 6.2% before
# and after on seeds 1 and 700000).
FRONT_WALL_PRIOR = (4.67, 0.22)
MEASUREMENT_SD = 0.1  # log error of one uncalibrated height measurement (edges, occlusion)
MIN_CALIBRATION_COUNT = 8  # fewer measurements of a class and its calibration is not used
MIN_CALIBRATED_SD = 0.05
# The measurements of one photo share errors (its pitch, its occluders), so the fused spread
# understates the real error: on 150 synthetic rooms (seeds 300000+) the errors were 1.17
# times the fused spread (root mean square of their ratio).
SPREAD_WIDENING = 1.2
# A measurement more than this many of its combined spreads (its own and the camera prior's)
# from the camera-height prior is dropped: a chair read as 3.25 m of camera height, or a
# bookshelf as 5 m, is a box that is not what its class says (stacked, cut, hidden), and a
# lone one would decide the scale since the others' median cannot reject it. 4 raised layout
# IoU on 150 rooms from seed 300000 69.4 -> 69.7 and on 100 from 700000 71.6 -> 71.8 (3 and
# 2.5 did about as well); seeds 7000 and 1 have no such outliers.
PRIOR_GATE = 4.0
# Classes standing on the floor whose bottom edge is where they meet it (doors included:
# their heights vary least of all, so they weigh most).
FLOOR_CLASSES = frozenset(
    {"bed", "sofa", "chair", "table", "desk", "dresser", "night_stand", "cabinet", "bookshelf",
     "shelves", "counter", "refrigerator", "toilet", "bathtub", "door"}
)  # fmt: skip
CALIBRATION_FILE = Path(__file__).parent.parent / "knowledge" / "scale_calibration.json"


@dataclass(frozen=True)
class ClassCalibration:
    bias: float  # mean of (measured - true) log camera height
    sd: float  # spread of the corrected measurement
    count: int


Measurement = Literal["height", "width", "mounting"]
MEASUREMENTS: tuple[Measurement, ...] = ("height", "width", "mounting")


@dataclass(frozen=True)
class ScaleCalibration:
    """Per measurement kind, per class: how far one measurement is off."""

    kinds: dict[Measurement, dict[str, ClassCalibration]] = field(default_factory=dict)
    source: str = "uncalibrated"

    def measurement_error(self, kind: Measurement, cls: str) -> tuple[float, float] | None:
        """(bias, sd) of one log camera-height measurement of `kind` from an object of class
        `cls`; None for a width or mounting that was not calibrated (they vary too much, or
        depend too much on the room's walls, to use raw)."""
        calibrated = self.kinds.get(kind, {}).get(cls)
        if calibrated is None or calibrated.count < MIN_CALIBRATION_COUNT:
            if kind != "height":
                return None
            return 0.0, math.hypot(height_spread(cls), MEASUREMENT_SD)
        return calibrated.bias, max(calibrated.sd, MIN_CALIBRATED_SD)

    def to_json(self) -> str:
        kinds = {
            kind: {
                cls: {"bias": round(c.bias, 4), "sd": round(c.sd, 4), "count": c.count}
                for cls, c in sorted(classes.items())
            }
            for kind, classes in self.kinds.items()
        }
        return json.dumps({"source": self.source, **kinds}, indent=2) + "\n"

    @classmethod
    def from_json(cls, text: str) -> ScaleCalibration:
        data = json.loads(text)
        kinds: dict[Measurement, dict[str, ClassCalibration]] = {
            kind: {name: ClassCalibration(**values) for name, values in data[kind].items()}
            for kind in MEASUREMENTS
            if kind in data
        }
        return cls(kinds=kinds, source=data["source"])


@lru_cache(maxsize=1)
def default_calibration() -> ScaleCalibration:
    if not CALIBRATION_FILE.is_file():
        return ScaleCalibration()
    return ScaleCalibration.from_json(CALIBRATION_FILE.read_text())


def floor_contacts(
    camera: PinholeCamera, objects: list[SceneObject], height: int
) -> list[tuple[SceneObject, FloatArray]]:
    """Floor points (camera height 1) under furniture whose bottom edge is in the photo."""
    out = []
    for obj in objects:
        x1, _, x2, y2 = obj.bbox
        if obj.cls not in FLOOR_CLASSES or y2 >= height - 2:
            continue
        hits = hit_horizontal_plane(camera, np.array([[(x1 + x2) / 2, y2]]), -1.0)
        if hits is not None:
            out.append((obj, hits[0]))
    return out


def _inside_another_box(
    obj: SceneObject, objects: list[SceneObject], x: float, y: float, bottom_margin: float = 0.0
) -> bool:
    """Whether the pixel (x, y) lies inside the box of an object other than `obj` (at least
    `bottom_margin` above that box's bottom edge)."""
    return any(
        o is not obj and o.bbox[0] < x < o.bbox[2] and o.bbox[1] < y < o.bbox[3] - bottom_margin
        for o in objects
    )


def bottom_may_be_hidden(obj: SceneObject, objects: list[SceneObject]) -> bool:
    """Whether the middle of the box's bottom edge lies inside the box of an object that
    reaches lower in the photo (nearer the camera, so possibly in front of it): the box then
    ends where the view is cut off, and its floor contact may lie too far away, even beyond
    the walls. (The scale still uses such objects: its calibration counts that error in.)"""
    x1, _, x2, y2 = obj.bbox
    return _inside_another_box(obj, objects, (x1 + x2) / 2, y2, bottom_margin=2)


# A floor contact is not believed when the object, standing there, would be TOO_LARGE_FACTOR
# times the largest size its class allows even with a camera LOWEST_CAMERA_M high (the camera
# prior less PRIOR_GATE spreads: 0.87 m). The limits per class, in camera heights, are the
# shared contract's TOO_LARGE_LIMITS (the browser's live suggestions apply them too); the
# tests hold them to the furniture library's sizes. None of 401 contacts in 40 synthetic
# rooms comes near a limit; on real photos it is a shelf hung on a wall, cut by the photo's
# top and side, whose bottom edge read as a floor contact 12 m away made a room 16 m long.
TOO_LARGE_FACTOR = 1.5
LOWEST_CAMERA_M = CAMERA_HEIGHT_PRIOR[0] * math.exp(-PRIOR_GATE * CAMERA_HEIGHT_PRIOR[1])


def too_large_to_stand_there(camera: PinholeCamera, cls: str, bbox: list[float]) -> bool:
    """Whether an object of class `cls` would be far larger than its class allows if it stood
    on the floor where its box's bottom edge meets it: what the photo shows of it (a lower
    bound when it is cut off) spans too much of the floor or rises too high there. Such an
    object is not on the floor, or its bottom is hidden: its contact says nothing about where
    the room ends. False for a class of no known size, or a bottom edge off the floor."""
    limits = TOO_LARGE_LIMITS.get(cls)
    x1, y1, x2, y2 = bbox
    hits = hit_horizontal_plane(camera, np.array([[x1, y2], [x2, y2], [(x1 + x2) / 2, y2]]), -1.0)
    if limits is None or hits is None:
        return False
    span = float(np.linalg.norm(hits[0] - hits[1]))
    rise = height_above(camera, hits[2], np.array([[(x1 + x2) / 2, y1]]))
    return span > limits[0] or rise > limits[1]


def measured_log_camera_height(
    camera: PinholeCamera, obj: SceneObject, base: FloatArray
) -> float | None:
    """log(camera height in metres) implied by the object's typical height, uncorrected; None
    when its top is cut off or the vertical through its contact gives no height.

    Seen from above, a box's top edge in the photo is its far top edge, about one depth
    behind the contact point: the vertical is moved back by the class's depth (in units of
    the camera height, so a few fixed-point steps)."""
    x1, y1, x2, _ = obj.bbox
    if y1 <= 2:
        return None
    depth, height, _ = middle_size(obj.cls)
    heading = np.array([base[0], 0.0, base[2]]) / max(float(np.hypot(base[0], base[2])), 1e-9)
    metres = CAMERA_HEIGHT_PRIOR[0]
    for _ in range(3):
        unit_height = height_above(
            camera, base + heading * depth / metres, np.array([[(x1 + x2) / 2, y1]])
        )
        if unit_height <= 0.05:
            return None
        metres = height / unit_height
    return math.log(metres)


def measured_log_camera_height_from_width(
    camera: PinholeCamera, obj: SceneObject, image_width: int
) -> float | None:
    """log(camera height in metres) implied by the object's typical width, uncorrected: the
    box's bottom edge laid on the floor at its nearest point spans about the object's larger
    horizontal side (the calibration absorbs how it is turned); None when a side is cut off."""
    x1, _, x2, y2 = obj.bbox
    if x1 <= 2 or x2 >= image_width - 2:
        return None
    hits = hit_horizontal_plane(camera, np.array([[x1, y2], [x2, y2]]), -1.0)
    if hits is None or np.isnan(hits).any():
        return None
    apparent = float(np.linalg.norm(hits[0] - hits[1]))
    depth, _, width = middle_size(obj.cls)
    return math.log(max(width, depth) / apparent) if apparent > 0.02 else None


def measurements(
    camera: PinholeCamera, obj: SceneObject, base: FloatArray, image_width: int
) -> Iterator[tuple[Measurement, float]]:
    """Every uncorrected log camera-height measurement the object offers."""
    height = measured_log_camera_height(camera, obj, base)
    if height is not None:
        yield "height", height
    width = measured_log_camera_height_from_width(camera, obj, image_width)
    if width is not None:
        yield "width", width


def mounting_points(
    objects: list[SceneObject], image_height: int
) -> list[tuple[SceneObject, FloatArray]]:
    """The two ends (2, 2) of the lower edge of each thing hung on a wall, as its box shows
    it: a horizontal edge on a wall reaches the box's bottom line only at its nearer end, so
    of the two rays the one meeting the wall highest is the true one. Edges the photo cuts off
    are left out, and so are edges touching another object's box: the object may stand on
    that furniture (a television on a dresser), or the furniture may hide the edge."""
    out = []
    for obj in objects:
        if mounting_height(obj.cls) is None:
            continue
        x1, _, x2, bottom = obj.bbox
        if bottom >= image_height - 2:
            continue
        # 3 px below the edge: a television's box ends where the dresser's top begins.
        if any(_inside_another_box(obj, objects, x, bottom + 3) for x in (x1, (x1 + x2) / 2, x2)):
            continue
        out.append((obj, np.array([[x1, bottom], [x2, bottom]])))
    return out


def measured_log_camera_height_from_mounting(obj: SceneObject, height: float) -> float | None:
    """log(camera height in metres) implied by the typical height of the object's lower edge,
    seen `height` camera heights above the floor; None for an edge at or below the floor."""
    typical = mounting_height(obj.cls)
    if typical is None or not height > 0.05:
        return None
    return math.log(typical / height)


@dataclass(frozen=True)
class ScaleEstimate:
    metres: float  # the camera's height: metres per unit
    spread: float  # how far off it may be: standard deviation of log(metres)
    priors: str  # which priors decided it

    def describe(self) -> str:
        return f"{self.priors}, about ±{100 * self.spread:.0f}%"


Mounted = list[tuple[SceneObject, float]]  # things on walls, lower edges' heights (camera heights)


def object_measurements(
    camera: PinholeCamera,
    contacts: list[tuple[SceneObject, FloatArray]],
    mounted: Mounted,
    image_width: int,
) -> Iterator[tuple[SceneObject, Measurement, float]]:
    """Every uncorrected log camera-height measurement the objects offer."""
    for obj, base in contacts:
        for kind, measured in measurements(camera, obj, base, image_width):
            yield obj, kind, measured
    for obj, height in mounted:
        on_wall = measured_log_camera_height_from_mounting(obj, height)
        if on_wall is not None:
            yield obj, "mounting", on_wall


LogMeasurement = tuple[float, float]  # (log metres per camera height, sd of that log)


def room_priors(
    ceiling_above_camera: float | None, front_wall: float | None = None
) -> list[LogMeasurement]:
    """The priors every photo starts from: the camera's height, the room's height when the
    ceiling is seen `ceiling_above_camera` camera heights above the camera, and the distance
    to the wall the camera faces when it is seen `front_wall` camera heights away."""
    logs = [(math.log(CAMERA_HEIGHT_PRIOR[0]), CAMERA_HEIGHT_PRIOR[1])]
    if ceiling_above_camera is not None:
        room_log = math.log(ROOM_HEIGHT_PRIOR[0] / (1.0 + ceiling_above_camera))
        logs.append((room_log, ROOM_HEIGHT_PRIOR[1]))
    if front_wall is not None:
        logs.append((math.log(FRONT_WALL_PRIOR[0] / front_wall), FRONT_WALL_PRIOR[1]))
    return logs


def fuse(logs: list[LogMeasurement]) -> tuple[float, float]:
    """Inverse-variance mean of log measurements: (metres, sd of the fused log)."""
    weights = np.array([1 / sd**2 for _, sd in logs])
    values = np.array([v for v, _ in logs])
    return float(math.exp((weights @ values) / weights.sum())), 1 / math.sqrt(weights.sum())


def camera_height(
    camera: PinholeCamera,
    contacts: list[tuple[SceneObject, FloatArray]],
    ceiling_above_camera: float | None,
    image_width: int,
    calibration: ScaleCalibration | None = None,
    mounted: Mounted | None = None,
    front_wall: float | None = None,
) -> ScaleEstimate:
    """The camera's height in metres (metres per unit), how far off it may be, and which
    priors decided it. `ceiling_above_camera` is the seen ceiling's height in camera heights,
    or None; `mounted` are things on walls with the heights of their lower edges (camera
    heights), and `front_wall` the seen front wall's distance, when the room is known."""
    calibration = calibration or default_calibration()
    logs = room_priors(ceiling_above_camera, front_wall)
    used = ["camera height"] + (["room height"] if ceiling_above_camera is not None else [])
    used += ["front wall distance"] if front_wall is not None else []
    prior_log, prior_sd = math.log(CAMERA_HEIGHT_PRIOR[0]), CAMERA_HEIGHT_PRIOR[1]
    sized: list[tuple[float, float, Measurement]] = []
    for obj, kind, measured in object_measurements(camera, contacts, mounted or [], image_width):
        error = calibration.measurement_error(kind, obj.cls)
        if error is None:
            continue
        corrected, sd = measured - error[0], error[1]
        if abs(corrected - prior_log) < PRIOR_GATE * math.hypot(sd, prior_sd):
            sized.append((corrected, sd, kind))
    if sized:
        # Drop measurements far from the others (a box measured across an occluder, say).
        centre = float(np.median([e for e, _, _ in sized]))
        kept = [(e, sd, kind) for e, sd, kind in sized if abs(e - centre) < 2.5 * sd]
        logs += [(e, sd) for e, sd, _ in kept]
        on_walls = sum(kind == "mounting" for _, _, kind in kept)
        if len(kept) > on_walls:
            used.append(f"{len(kept) - on_walls} object height(s) and width(s)")
        if on_walls:
            used.append(f"{on_walls} wall object(s)")
    metres, spread = fuse(logs)
    return ScaleEstimate(metres=metres, spread=SPREAD_WIDENING * spread, priors=" + ".join(used))


Residual = tuple[Measurement, str, float]  # (kind, class, measured - true log camera height)


def measurement_residuals(
    camera: PinholeCamera,
    contacts: list[tuple[SceneObject, FloatArray]],
    mounted: Mounted,
    true_camera_height: float,
    image_width: int,
) -> Iterator[Residual]:
    """Every measurement of every object that can be measured, against the truth."""
    for obj, kind, measured in object_measurements(camera, contacts, mounted, image_width):
        yield kind, obj.cls, measured - math.log(true_camera_height)


def fit_calibration(residuals: Iterable[Residual], source: str) -> ScaleCalibration:
    """Per kind and class: bias (the median, robust to the odd occluded box) and spread
    (1.4826 times the median absolute deviation)."""
    grouped: dict[Measurement, dict[str, list[float]]] = defaultdict(lambda: defaultdict(list))
    for kind, cls, value in residuals:
        grouped[kind][cls].append(value)
    kinds: dict[Measurement, dict[str, ClassCalibration]] = {}
    for kind, by_class in grouped.items():
        kinds[kind] = {}
        for cls, values in by_class.items():
            array = np.array(values)
            median = float(np.median(array))
            spread = 1.4826 * float(np.median(np.abs(array - median)))
            kinds[kind][cls] = ClassCalibration(bias=median, sd=spread, count=len(values))
    return ScaleCalibration(kinds=kinds, source=source)
