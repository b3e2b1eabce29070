"""Single-view metrology of object heights (thesis Section 4.4.1, Eq. 4.3; Criminisi 2000).

An object's height line is the longest vertical edge of its silhouette: rays from the vertical
vanishing point through the mask's boundary pixels are binned by angle (a kernel density),
the local maxima are the silhouette's vertical edges, and the longest run of boundary pixels
along one of them gives the top t and bottom b.

Heights are measured against the room height line (a vertical edge of the layout, bottom
b_r on the floor, top t_r on the ceiling, real height H_r) by the cross ratio

    A / H_r = |x - b_r| / |t_r - b_r| * |vp_v - t_r| / |vp_v - x|

for a point x on the room line at altitude A. A point p off the room line is first carried
onto it along a horizontal direction: the line from its foot f (a point on the same vertical
whose altitude is known) to the room line's point at that altitude meets the horizon in a
vanishing point u, and the line u-p meets the room line at the image of p's altitude. This is
the thesis's recursion: an object standing on the floor has its foot at altitude 0; one
supported from below by O_j has its bottom at O_j's top altitude A_j, so H_i = A_i - A_j; an
object on a wall takes the foot of its vertical where the wall meets the floor, and its
height is the difference of its top and bottom altitudes.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Literal

import cv2
import numpy as np
from holiscene_schema import SupportRelation

from ..geometry.boxes import box_corners
from ..geometry.camera import FloatArray
from ..shapes import SIZE_RANGES
from .room import Room

Prior = tuple[float, float]  # mean, standard deviation (metres)
_DEFAULT_PRIOR: Prior = (0.6, 0.3)


def height_prior(cls: str) -> Prior:
    """Mean and standard deviation of a class's height: the library's range taken as a
    uniform distribution (std = range / sqrt(12))."""
    ranges = SIZE_RANGES.get(cls)
    if ranges is None:
        return _DEFAULT_PRIOR
    lo, hi = ranges.height
    return (lo + hi) / 2.0, max((hi - lo) / math.sqrt(12.0), 0.05 * (lo + hi) / 2.0)


def within_three_sigma(height: float, prior: Prior) -> bool:
    mean, std = prior
    return bool(np.isfinite(height)) and abs(height - mean) <= 3.0 * std


def _h(point: FloatArray) -> FloatArray:
    return np.array([float(point[0]), float(point[1]), 1.0])


def _dehom(point: FloatArray) -> FloatArray | None:
    if abs(point[2]) < 1e-12:
        return None
    result: FloatArray = point[:2] / point[2]
    return result


@dataclass(frozen=True)
class RoomReference:
    """The room height line with the vertical vanishing point and the horizon."""

    vertical_vp: FloatArray  # homogeneous (3,)
    horizon: FloatArray  # homogeneous line (3,)
    bottom: FloatArray  # b_r, pixel (2,), on the floor
    top: FloatArray  # t_r, pixel (2,), on the ceiling
    room_height: float  # H_r, metres

    @property
    def _direction(self) -> FloatArray:
        result: FloatArray = self.top - self.bottom
        return result

    def _k(self) -> float:
        """1 / (the vanishing point's parameter s on the line b_r + s (t_r - b_r))."""
        d = self._direction
        v = self.vertical_vp
        denom = float((v[:2] - v[2] * self.bottom) @ d)
        if abs(denom) < 1e-12:
            return 0.0
        return float(v[2] * (d @ d) / denom)

    def _param(self, x: FloatArray) -> float:
        d = self._direction
        return float((x - self.bottom) @ d / (d @ d))

    def altitude_on_line(self, x: FloatArray) -> float:
        """Eq. 4.3 for a point on the room line."""
        s, k = self._param(x), self._k()
        denom = 1.0 - s * k
        if abs(denom) < 1e-12:
            return math.inf
        return self.room_height * s * (1.0 - k) / denom

    def point_at_altitude(self, altitude: float) -> FloatArray:
        q, k = altitude / self.room_height, self._k()
        s = q / (1.0 - k + q * k)
        result: FloatArray = self.bottom + s * self._direction
        return result

    def altitude(self, point: FloatArray, foot: FloatArray, foot_altitude: float) -> float:
        """Altitude of `point` given a point `foot` on the same vertical at a known altitude."""
        reference = self.point_at_altitude(foot_altitude)
        room_line = np.cross(_h(self.bottom), _h(self.top))
        if float(np.linalg.norm(reference - foot)) < 1e-6:
            carried: FloatArray | None = np.asarray(point, dtype=float)
        else:
            to_horizon = np.cross(_h(reference), _h(foot))
            u = np.cross(to_horizon, self.horizon)
            carried = _dehom(np.cross(np.cross(u, _h(point)), room_line))
        if carried is None:
            return math.nan
        return self.altitude_on_line(carried)


@dataclass(frozen=True)
class HeightLine:
    top: FloatArray  # pixel (2,)
    bottom: FloatArray
    top_clear: bool  # nothing hides the top (not at the border, no other mask beyond it)
    bottom_clear: bool

    @property
    def length(self) -> float:
        return float(np.linalg.norm(self.top - self.bottom))


def _boundary(mask: np.ndarray) -> np.ndarray:
    m = mask.astype(np.uint8)
    eroded = cv2.erode(m, np.ones((3, 3), np.uint8), borderType=cv2.BORDER_CONSTANT, borderValue=0)
    result: np.ndarray = (m > 0) & (eroded == 0)
    return result


def _clear(
    point: FloatArray,
    outward: FloatArray,
    labels: np.ndarray | None,
    allowed: frozenset[int],
    shape: tuple[int, int],
) -> bool:
    """No image border and no other object's mask within a few pixels beyond `point`."""
    height, width = shape
    across = np.array([-outward[1], outward[0]])
    for step in (1.5, 3.0, 4.5):
        for side in (-1.0, 0.0, 1.0):
            x, y = point + outward * step + across * side
            if not (1.0 <= x < width - 1.0 and 1.0 <= y < height - 1.0):
                return False
            if labels is not None:
                label = int(labels[int(y), int(x)])
                if label >= 0 and label not in allowed:
                    return False
    return True


def height_lines(
    mask: np.ndarray,
    vertical_vp: FloatArray,
    labels: np.ndarray | None = None,
    allowed_below: frozenset[int] = frozenset(),
    allowed_above: frozenset[int] | None = frozenset(),
    max_lines: int = 6,
) -> list[HeightLine]:
    """Candidate height lines of a mask, longest first (the thesis takes the first).

    `labels` (int, -1 where no object) marks other objects' pixels: a line's end is not clear
    when one of them lies just beyond it, unless its label is allowed there (the supporter
    below, the objects it holds up above); `allowed_above=None` checks only the border."""
    rows, cols = np.flatnonzero(mask.any(axis=1)), np.flatnonzero(mask.any(axis=0))
    if len(rows) == 0:
        return []
    y0, y1 = max(int(rows[0]) - 1, 0), int(rows[-1]) + 2
    x0, x1 = max(int(cols[0]) - 1, 0), int(cols[-1]) + 2
    boundary = _boundary(np.pad(mask[y0:y1, x0:x1], 1))[1:-1, 1:-1]
    ys, xs = np.nonzero(boundary)
    if len(xs) < 6:
        return []
    pts = np.column_stack([xs + x0 + 0.5, ys + y0 + 0.5])
    v = np.asarray(vertical_vp, dtype=float)
    far = abs(v[2]) < 1e-9 * max(1.0, float(np.linalg.norm(v[:2])))
    if not far:
        centre = v[:2] / v[2]
        rel = pts - centre
        along = np.linalg.norm(rel, axis=1)
        far = float(np.median(along)) > 1e7
    if far:
        direction = v[:2] / max(float(np.linalg.norm(v[:2])), 1e-12)
        coord = pts @ np.array([-direction[1], direction[0]])  # pixels across the rays
        along = pts @ direction
        bin_width = 1.0
    else:
        mean = rel.mean(axis=0)
        mean /= max(float(np.linalg.norm(mean)), 1e-12)
        coord = np.arctan2(rel @ np.array([-mean[1], mean[0]]), rel @ mean)
        bin_width = 1.0 / float(np.median(along))
    lo = float(coord.min())
    index = np.floor((coord - lo) / bin_width).astype(int)
    counts = np.bincount(index).astype(float)
    kernel = np.array([1.0, 2.0, 3.0, 2.0, 1.0]) / 9.0
    # Centred on each bin; mode="same" would pad to the kernel's length (and shift the bins)
    # for a silhouette only a few bins wide, leaving peaks with no boundary pixels.
    density = np.convolve(counts, kernel, mode="full")[2 : 2 + len(counts)]
    padded = np.concatenate([[-1.0], density, [-1.0]])
    peaks = np.flatnonzero((density >= padded[:-2]) & (density > padded[2:]) & (density >= 3.0))
    peaks = peaks[np.argsort(-density[peaks])][: max_lines * 3]
    lines: list[tuple[float, HeightLine]] = []
    for peak in peaks:
        near = np.flatnonzero(np.abs(index - peak) <= 1)
        order = near[np.argsort(along[near])]
        r = along[order]
        gaps = np.flatnonzero(np.diff(r) > 2.5)
        starts = np.concatenate([[0], gaps + 1])
        ends = np.concatenate([gaps, [len(r) - 1]])
        best = int(np.argmax(r[ends] - r[starts]))
        a, b = pts[order[starts[best]]], pts[order[ends[best]]]
        if abs(a[1] - b[1]) < 3.0:
            continue
        top, bottom = (a, b) if a[1] < b[1] else (b, a)
        down = (bottom - top) / max(float(np.linalg.norm(bottom - top)), 1e-9)
        line = HeightLine(
            top=top,
            bottom=bottom,
            top_clear=_clear(
                top,
                -down,
                labels if allowed_above is not None else None,
                allowed_above or frozenset(),
                mask.shape,
            ),
            bottom_clear=_clear(bottom, down, labels, allowed_below, mask.shape),
        )
        lines.append((line.length, line))
    lines.sort(key=lambda item: -item[0])
    return [line for _, line in lines[:max_lines]]


def room_reference(
    projection: FloatArray, room: Room, vanishing_points: FloatArray, image_size: tuple[int, int]
) -> RoomReference | None:
    """The room's vertical edge nearest the image centre, in front of the camera, as the
    reference height line; the horizon through the two horizontal vanishing points."""
    corners = box_corners(room.centre, room.size, room.yaw_deg)
    homogeneous = corners @ projection.T
    width, height = image_size
    centre = np.array([width / 2.0, height / 2.0])
    best: tuple[float, FloatArray, FloatArray] | None = None
    for k in range(4):
        bottom_h, top_h = homogeneous[k], homogeneous[k + 4]
        if bottom_h[2] <= 1e-6 or top_h[2] <= 1e-6:
            continue
        bottom, top = bottom_h[:2] / bottom_h[2], top_h[:2] / top_h[2]
        distance = float(np.linalg.norm((bottom + top) / 2.0 - centre))
        if np.linalg.norm(top - bottom) > 1.0 and (best is None or distance < best[0]):
            best = (distance, bottom, top)
    vps = np.asarray(vanishing_points, dtype=float)
    horizon = np.cross(vps[1], vps[2])
    if best is None or float(np.linalg.norm(horizon)) < 1e-12:
        return None
    return RoomReference(
        vertical_vp=vps[0] / np.linalg.norm(vps[0]),
        horizon=horizon / np.linalg.norm(horizon),
        bottom=best[1],
        top=best[2],
        room_height=float(room.size[1]),
    )


HeightSource = Literal["measured", "lower_bound", "prior"]
# The reason of a measurement refused as beyond three standard deviations of its class.
OUTSIDE_PRIOR = "measured outside its class's range"


@dataclass(frozen=True)
class HeightEstimate:
    height: float
    bottom_altitude: float  # above the floor
    source: HeightSource
    reason: str | None = None
    # What was measured when it was refused as outside the class's range (source "prior").
    measured: float | None = None

    @property
    def top_altitude(self) -> float:
        return self.bottom_altitude + self.height


def _object_labels(masks: dict[str, np.ndarray], ids: list[str]) -> np.ndarray:
    first = next(iter(masks.values()))
    labels = np.full(first.shape, -1, dtype=np.int32)
    for index, obj_id in enumerate(ids):
        mask = masks.get(obj_id)
        if mask is not None:
            labels[mask] = index
    return labels


def _line_through(a: FloatArray, b: FloatArray) -> FloatArray:
    result: FloatArray = np.cross(a, b)
    return result


class HeightMeter:
    """Measures every object's height along the support order (parents first)."""

    def __init__(
        self,
        reference: RoomReference,
        room: Room,
        projection: FloatArray,
        masks: dict[str, np.ndarray],
        classes: dict[str, str],
        supports: dict[str, SupportRelation],
        horizontal_vps: FloatArray,
    ) -> None:
        self.reference = reference
        self.room = room
        self.projection = projection
        self.masks = masks
        self.classes = classes
        self.supports = supports
        self.horizontal_vps = horizontal_vps
        self.ids = list(classes)
        self.index = {obj_id: i for i, obj_id in enumerate(self.ids)}
        self.labels = _object_labels(masks, self.ids)
        self.children: dict[str, set[int]] = {}
        for child, support in supports.items():
            if child in self.index:
                self.children.setdefault(support.parent, set()).add(self.index[child])
        self.estimates: dict[str, HeightEstimate] = {}

    def measure(self, obj_id: str) -> HeightEstimate:
        estimate = self._measure(obj_id)
        self.estimates[obj_id] = estimate
        return estimate

    def _lines(self, obj_id: str, parent: str | None) -> list[HeightLine]:
        mask = self.masks.get(obj_id)
        if mask is None or not mask.any():
            return []
        own = {self.index[obj_id]}
        below = frozenset(own | ({self.index[parent]} if parent in self.index else set()))
        # Beyond a visible top there may be an object behind this one as well as one in
        # front of it, so only the image border counts as hiding the top; just below the
        # visible bottom, another object is in front of this one (or holds it up).
        return height_lines(mask, self.reference.vertical_vp, self.labels, below, None)

    def _measure(self, obj_id: str) -> HeightEstimate:
        prior = height_prior(self.classes[obj_id])
        support = self.supports.get(obj_id)
        parent = support.parent if support is not None else "floor"
        kind = support.type if support is not None else "below"
        lines = self._lines(obj_id, parent)
        if kind == "below" and parent != "ceiling":
            base = 0.0
            if parent in self.index:
                parent_estimate = self.estimates.get(parent)
                if parent_estimate is None:
                    return self._prior(prior, 0.0, "its supporter has no height")
                base = parent_estimate.top_altitude
            return self._standing(obj_id, lines, base, parent, prior)
        if parent == "ceiling":
            return self._hanging(lines, prior)
        return self._attached(obj_id, lines, parent, prior)

    def _prior(
        self, prior: Prior, base: float, reason: str, measured: float | None = None
    ) -> HeightEstimate:
        return HeightEstimate(prior[0], base, "prior", reason, measured)

    def _checked(
        self, height: float, base: float, prior: Prior, lower_bound: bool
    ) -> HeightEstimate:
        if lower_bound and np.isfinite(height):
            height = max(height, prior[0])
            if within_three_sigma(height, prior):
                return HeightEstimate(height, base, "lower_bound", "top hidden: at least this")
        if not within_three_sigma(height, prior) or height <= 0.01:
            if not np.isfinite(height) or height <= 0.01:
                # A negative or no value says the measurement failed, not that the object is
                # tiny: shown as such, not as a number a reviewer would puzzle over.
                return self._prior(prior, base, "no positive height measured")
            return self._prior(prior, base, OUTSIDE_PRIOR, float(height))
        return HeightEstimate(height, base, "measured")

    def _standing(
        self, obj_id: str, lines: list[HeightLine], base: float, parent: str, prior: Prior
    ) -> HeightEstimate:
        """Eq. 4.3 from the floor up: the bottom b_i stands at its supporter's top A_j.

        When that gives no plausible height, the object stands on a lower surface inside its
        supporter (a shelf, a mattress below a headboard): its vertical's foot is then taken
        on the supporter's front, reached from the supporter's own foot along a room axis.
        """
        usable = [line for line in lines if line.bottom_clear]
        if not usable:
            reason = "bottom hidden" if lines else "no vertical edge in the mask"
            return self._prior(prior, base, reason)
        line = usable[0]
        top = self.reference.altitude(line.top, line.bottom, base)
        on_top = self._checked(top - base, base, prior, not line.top_clear)
        if on_top.source != "prior" or parent not in self.index:
            return on_top
        inside = [
            self._checked(top_alt - bottom_alt, bottom_alt, prior, not line.top_clear)
            for bottom_alt, top_alt in self._inside(line, parent, base)
        ]
        plausible = [e for e in inside if e.source != "prior"]
        if not plausible:
            return on_top
        return min(plausible, key=lambda e: abs(e.height - prior[0]))

    def _inside(
        self, line: HeightLine, parent: str, parent_top: float
    ) -> list[tuple[float, float]]:
        """(bottom, top) altitudes of a line whose foot lies on a face of its supporter."""
        parent_estimate = self.estimates.get(parent)
        parent_lines = self._lines(parent, self._parent_of(parent))
        if parent_estimate is None or not parent_lines:
            return []
        parent_foot = _h(parent_lines[0].bottom)
        vertical = _line_through(self.reference.vertical_vp, _h(line.bottom))
        out = []
        for vp in self.horizontal_vps:
            foot = _dehom(np.cross(_line_through(vp, parent_foot), vertical))
            if foot is None:
                continue
            base = parent_estimate.bottom_altitude
            bottom = self.reference.altitude(line.bottom, foot, base)
            top = self.reference.altitude(line.top, foot, base)
            if base - 0.02 <= bottom <= parent_top + 0.02:
                out.append((bottom, top))
        return out

    def _parent_of(self, obj_id: str) -> str | None:
        support = self.supports.get(obj_id)
        return support.parent if support is not None else None

    def _hanging(self, lines: list[HeightLine], prior: Prior) -> HeightEstimate:
        ceiling = self.reference.room_height
        usable = [line for line in lines if line.top_clear]
        if not usable:
            return self._prior(prior, ceiling - prior[0], "top hidden")
        line = next((ln for ln in usable if ln.bottom_clear), usable[0])
        bottom = self.reference.altitude(line.bottom, line.top, ceiling)
        estimate = self._checked(ceiling - bottom, bottom, prior, not line.bottom_clear)
        return HeightEstimate(
            estimate.height, ceiling - estimate.height, estimate.source, estimate.reason
        )

    def _attached(
        self, obj_id: str, lines: list[HeightLine], parent: str, prior: Prior
    ) -> HeightEstimate:
        """Supported from behind: both ends measured from the foot of their vertical on the
        floor, under the wall (or under the supporting object's face)."""
        if not lines:
            return self._prior(prior, 1.0, "no vertical edge in the mask")
        line = next((ln for ln in lines if ln.top_clear and ln.bottom_clear), lines[0])
        foot = self._foot(obj_id, line, parent)
        if foot is None:
            return self._prior(prior, 1.0, "no floor line under it")
        bottom = self.reference.altitude(line.bottom, foot, 0.0)
        top = self.reference.altitude(line.top, foot, 0.0)
        hidden = not (line.top_clear and line.bottom_clear)
        return self._checked(top - bottom, bottom, prior, hidden)

    def _foot(self, obj_id: str, line: HeightLine, parent: str) -> FloatArray | None:
        vertical = _line_through(self.reference.vertical_vp, _h(line.bottom))
        parent_estimate = self.estimates.get(parent)
        parent_lines = self._lines(parent, None) if parent in self.index else []
        if parent_estimate is not None and parent_lines:
            # The supporting object's face: from its foot along a room axis to our vertical.
            parent_foot = _h(parent_lines[0].bottom)
            best: FloatArray | None = None
            best_slope = math.inf
            for vp in self.horizontal_vps:
                along = _line_through(vp, parent_foot)
                foot = _dehom(np.cross(along, vertical))
                slope = abs(float(along[0]) / max(abs(float(along[1])), 1e-12))
                if foot is not None and slope < best_slope:
                    best, best_slope = foot, slope
            return best
        mask = self.masks[obj_id]
        ys, xs = np.nonzero(mask)
        centre = np.array([[xs.mean() + 0.5, ys.mean() + 0.5]])
        ray = np.linalg.solve(self.projection, _h(centre[0]))
        walls = self.room.walls_by_ray(ray / np.linalg.norm(ray))
        if not walls:
            return None
        wall = walls[0]
        ends = np.array(
            [
                wall.point(-wall.half_length, self.room.floor_y),
                wall.point(wall.half_length, self.room.floor_y),
            ]
        )
        edge = ends @ self.projection.T
        return _dehom(np.cross(np.cross(edge[0], edge[1]), vertical))
