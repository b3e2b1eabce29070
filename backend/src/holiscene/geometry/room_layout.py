"""The room cuboid from line segments, in units of the camera height (Hedau-style hypotheses).

With the camera's pitch and roll and the room's yaw known (`manhattan.py`), a room is the
distances from the camera to its front, left, right and back walls and its ceiling. Segments
of the two horizontal families vote for wall distances where they meet the floor (and, scaled
by the ceiling's unknown height, the ceiling); the best few values of each form hypotheses,
and each hypothesis is scored by how much segment length lies along its projected edges
(floor and ceiling edges, and the vertical corners between walls), subject to containing the
floor-standing objects. Units: camera height = 1, so the floor is y = -1.
"""

from __future__ import annotations

import dataclasses
import itertools
import math
from collections.abc import Callable
from dataclasses import dataclass

import cv2
import numpy as np
from numpy.typing import NDArray

from .camera import FloatArray, PinholeCamera
from .lines import Segments
from .manhattan import ManhattanFrame, room_directions
from .surface_labels import SURFACES, hit_distances, nearest_surface
from .surface_map import SurfaceMap

BACK_WALL_PRIOR = 0.5  # the wall behind the camera is never seen: its distance is a prior
CEILING_PRIOR = 0.96  # ceiling above the camera / camera height (2.75 m room, 1.4 m camera)
EDGE_TOLERANCE_FRAC = 0.006  # of the image diagonal
PEAKS_PER_WALL = 4


@dataclass(frozen=True)
class RoomHypothesis:
    front: float  # distances from the camera along room x (front), -z (left), +z (right)
    left: float
    right: float
    back: float
    ceiling: float  # ceiling height above the camera, in camera heights
    score: float
    ceiling_seen: bool

    @classmethod
    def enclosing(cls, points_room: FloatArray) -> RoomHypothesis:
        """The room whose box just holds the points (room axes, camera heights, camera at the
        origin): a true room from its corners."""
        low, high = points_room.min(axis=0), points_room.max(axis=0)
        return cls(
            front=float(high[0]), left=float(-low[2]), right=float(high[2]),
            back=float(-low[0]), ceiling=float(high[1]), score=0.0, ceiling_seen=True,
        )  # fmt: skip

    def surfaces_seen(self, rays_room: FloatArray) -> NDArray[np.int64]:
        """The face of this room (an index into `surface_labels.SURFACES`) each ray meets."""
        return nearest_surface(
            rays_room, self.front, self.back, self.left, self.right, 1.0, self.ceiling
        )

    def faces_in_view(self, rays_room: FloatArray) -> set[str]:
        """The names (SURFACES) of the faces some ray meets first."""
        return {SURFACES[i] for i in np.unique(self.surfaces_seen(rays_room))}

    def nearest_out_of_view(self, wall: str, rays_room: FloatArray) -> float:
        """The nearest distance of `wall` (a wall's field, named as in SURFACES) at which no
        ray meets it before the room's other faces: how near a wall out of view can be."""
        t = hit_distances(
            rays_room, self.front, self.back, self.left, self.right, 1.0, self.ceiling
        )
        face = SURFACES.index(wall)
        others = np.delete(t, face, axis=1).min(axis=1)
        towards = np.isfinite(t[:, face]) & np.isfinite(others)
        if not towards.any():
            return 0.0
        # Along a ray the wall's hit distance grows in proportion to the wall's distance.
        per_unit_distance = t[towards, face] / getattr(self, wall)
        return float((others[towards] / per_unit_distance).max())

    def height_on_walls(self, rays_room: FloatArray) -> FloatArray:
        """Height above the floor (camera heights) where each ray meets this room's walls;
        NaN for a ray that meets the floor or the ceiling first, or no wall ahead."""
        faces = self.surfaces_seen(rays_room)
        walls = {"front": (0, self.front), "left": (2, -self.left), "right": (2, self.right)}
        heights = np.full(len(rays_room), np.nan)
        for name, (axis, plane) in walls.items():
            on = faces == SURFACES.index(name)
            heights[on] = 1.0 + rays_room[on, 1] * plane / rays_room[on, axis]
        return heights

    def corners_room(self) -> FloatArray:
        """The 8 corners in room axes (x, y, z) relative to the camera, contract order."""
        x0, x1, z0, z1 = -self.back, self.front, -self.left, self.right
        y0, y1 = -1.0, self.ceiling
        return np.array(
            [[x0, y0, z0], [x1, y0, z0], [x1, y0, z1], [x0, y0, z1],
             [x0, y1, z0], [x1, y1, z0], [x1, y1, z1], [x0, y1, z1]]
        )  # fmt: skip


def room_to_world(frame: ManhattanFrame) -> FloatArray:
    """Rotation taking room axes to the world frame (columns: room x, y, z in world)."""
    dirs = room_directions(frame.yaw_deg)
    return np.column_stack([dirs[1], dirs[0], dirs[2]])


def _plane_hits(camera: PinholeCamera, pixels: FloatArray, plane_y: float) -> FloatArray:
    """Where pixel rays meet the plane y = plane_y (NaN where they do not, in front)."""
    rays = camera.ray(pixels)
    with np.errstate(divide="ignore", invalid="ignore"):
        t = plane_y / rays[:, 1]
    hits = rays * t[:, None]
    hits[~(t > 0)] = np.nan
    result: FloatArray = hits
    return result


def _weighted_peaks(values: FloatArray, weights: FloatArray, count: int) -> list[float]:
    """Peaks of a smoothed, log-spaced histogram of distance votes."""
    ok = np.isfinite(values) & (values > 0.2) & (values < 25.0)
    if not ok.any():
        return []
    bins = np.geomspace(0.2, 25.0, 160)
    hist, edges = np.histogram(values[ok], bins=bins, weights=weights[ok])
    hist = np.convolve(hist, [0.25, 0.5, 0.25], mode="same")
    centres = np.sqrt(edges[:-1] * edges[1:])
    order = np.argsort(hist)[::-1]
    peaks: list[float] = []
    for i in order:
        if hist[i] <= 0 or len(peaks) == count:
            break
        if all(abs(math.log(centres[i] / p)) > 0.06 for p in peaks):
            peaks.append(float(centres[i]))
    return peaks


def _votes(
    camera: PinholeCamera,
    segments: Segments,
    family: NDArray[np.int64],
    to_room: FloatArray,
    plane_y: float,
) -> tuple[FloatArray, FloatArray, FloatArray, FloatArray]:
    """Room-axis coordinates of segments on a horizontal plane: x of room-z segments (front
    wall), z of room-x segments (side walls), with their lengths."""
    mids = segments.midpoints
    hits = _plane_hits(camera, mids, plane_y) @ to_room  # rows: room (x, y, z)
    fronts = family == 2
    sides = family == 1
    lengths = segments.lengths
    return hits[fronts, 0], lengths[fronts], hits[sides, 2], lengths[sides]


def _edge_score(
    camera: PinholeCamera,
    segments: Segments,
    family: NDArray[np.int64],
    edges: list[tuple[FloatArray, FloatArray, int]],
    tolerance: float,
) -> float:
    """Segment length lying along the projected edges (each edge checked against its family).
    All edges of a family are checked at once: the room search calls this hundreds of times
    per photo, and a loop over edges spent most of its time outside numpy."""
    starts = np.array([start for start, _, _ in edges])
    ends = np.array([end for _, end, _ in edges])
    families = np.array([fam for _, _, fam in edges])
    image = _visible_parts(camera, starts, ends)
    a, direction = image[:, :2], image[:, 2:] - image[:, :2]
    with np.errstate(invalid="ignore"):  # NaN rows: segments behind the camera
        length = np.hypot(direction[:, 0], direction[:, 1])
        usable: NDArray[np.bool_] = np.isfinite(length) & (length >= 1e-6)
    total = 0.0
    for fam in np.unique(families[usable]):
        rows = usable & (families == fam)
        segment_ends = segments.endpoints[family == fam]
        if len(segment_ends) == 0:
            continue
        origin, edge_length = a[rows][:, None, :], length[rows][:, None]  # (edges, 1, ...)
        unit = (direction[rows] / length[rows][:, None])[:, None, :]
        normal = np.concatenate([-unit[..., 1:], unit[..., :1]], axis=2)
        first, second = segment_ends[None, :, :2] - origin, segment_ends[None, :, 2:] - origin
        d1, d2 = (first * normal).sum(axis=2), (second * normal).sum(axis=2)
        t1, t2 = (first * unit).sum(axis=2), (second * unit).sum(axis=2)
        near = (np.abs(d1) < tolerance) & (np.abs(d2) < tolerance)
        overlap = np.clip(np.maximum(t1, t2), 0, edge_length) - np.clip(
            np.minimum(t1, t2), 0, edge_length
        )
        total += float(overlap[near].sum())
    return total


def _visible_parts(camera: PinholeCamera, starts: FloatArray, ends: FloatArray) -> FloatArray:
    """Image segments (N, 4: x1, y1, x2, y2) of the parts of 3D segments (N, 3 each) in front
    of the camera; NaN for a segment wholly behind it."""
    forward = camera.optical_axis
    near = 0.05
    ds, de = starts @ forward, ends @ forward
    with np.errstate(divide="ignore", invalid="ignore"):
        cut_starts = starts + (ends - starts) * ((near - ds) / (de - ds))[:, None]
        cut_ends = ends + (starts - ends) * ((near - de) / (ds - de))[:, None]
    starts = np.where((ds < near)[:, None], cut_starts, starts)
    ends = np.where((de < near)[:, None], cut_ends, ends)
    projected = camera.project(np.vstack([starts, ends]))
    image: FloatArray = np.hstack([projected[: len(starts)], projected[len(starts) :]])
    image[(ds < near) & (de < near)] = np.nan
    return image


class SurfaceEvidence:
    """Colour statistics for scoring the surfaces a hypothesis implies (floor, ceiling, walls).

    The photo is reduced to a coarse grid of Lab colours; pixels inside object boxes are left
    out (furniture hides the walls). A good room splits the rest into surfaces that are each
    of one colour, so the score is the share of colour variance the split explains.
    """

    def __init__(
        self,
        camera: PinholeCamera,
        image: NDArray[np.uint8],
        boxes: list[list[float]],
        to_room: FloatArray,
        cell: int = 8,
    ) -> None:

        height, width = image.shape[:2]
        small = cv2.resize(image, (width // cell, height // cell), interpolation=cv2.INTER_AREA)
        lab = cv2.cvtColor(small, cv2.COLOR_RGB2LAB).reshape(-1, 3).astype(np.float64)
        ys, xs = np.mgrid[0 : small.shape[0], 0 : small.shape[1]]
        pixels = np.column_stack([(xs.ravel() + 0.5) * cell, (ys.ravel() + 0.5) * cell])
        keep = np.ones(len(pixels), dtype=bool)
        for x1, y1, x2, y2 in boxes:
            keep &= ~(
                (pixels[:, 0] >= x1)
                & (pixels[:, 0] <= x2)
                & (pixels[:, 1] >= y1)
                & (pixels[:, 1] <= y2)
            )
        self.colours = lab[keep]
        self.rays_room = camera.ray(pixels[keep]) @ to_room  # room axes
        self.total = float(((self.colours - self.colours.mean(axis=0)) ** 2).sum()) or 1.0
        self.squares = float((self.colours**2).sum())

    def explained(self, hyp: RoomHypothesis) -> float:
        if len(self.colours) == 0:
            return 0.0
        label = hyp.surfaces_seen(self.rays_room)
        # Within-surface variance = sum of squares - sum over surfaces of |colour sum|^2 / count
        # (counted per surface in one pass instead of a mask per surface).
        count = np.bincount(label, minlength=len(SURFACES))
        sums = np.stack(
            [np.bincount(label, self.colours[:, c], len(SURFACES)) for c in range(3)], axis=1
        )
        seen = count > 0
        within = self.squares - float(((sums[seen] ** 2).sum(axis=1) / count[seen]).sum())
        return 1.0 - within / self.total


def estimate_room(
    camera: PinholeCamera,
    frame: ManhattanFrame,
    segments: Segments,
    size: tuple[int, int],
    floor_points: FloatArray | None = None,
    evidence: SurfaceEvidence | None = None,
    object_boxes: list[list[float]] | None = None,
    surface_map: SurfaceMap | None = None,
    *,
    metres: float,
) -> RoomHypothesis:
    """The best room for the segments; `floor_points` (N, 3, world, camera height 1) are
    points known to lie inside the room (where floor-standing objects touch the floor).
    Segments inside `object_boxes` are edges of objects, not of the room: they do not count.
    With a `surface_map` (the Surface Network's labels), agreeing with it counts most, and it
    decides whether the ceiling is seen. `metres` (the camera's height as the objects tell it)
    turns the priors on wall distances, in metres, into camera heights."""
    to_room = room_to_world(frame)  # room -> world; world -> room is its transpose
    family = frame.family.copy()
    if object_boxes:
        mids = segments.midpoints
        for x1, y1, x2, y2 in object_boxes:
            on_object = (
                (mids[:, 0] > x1) & (mids[:, 0] < x2) & (mids[:, 1] > y1) & (mids[:, 1] < y2)
            )
            family[on_object] = -1
    floor_x, floor_xw, floor_z, floor_zw = _votes(camera, segments, family, to_room, -1.0)
    ceil_x, ceil_xw, ceil_z, ceil_zw = _votes(camera, segments, family, to_room, 1.0)

    inside = np.zeros((0, 3)) if floor_points is None else floor_points @ to_room
    min_front = float(inside[:, 0].max()) + 0.2 if len(inside) else 1.0
    min_left = float(-inside[:, 2].min()) + 0.2 if len(inside) else 0.3
    min_right = float(inside[:, 2].max()) + 0.2 if len(inside) else 0.3

    fronts = [f for f in _weighted_peaks(floor_x, floor_xw, PEAKS_PER_WALL) if f >= min_front]
    lefts = [v for v in _weighted_peaks(-floor_z, floor_zw, PEAKS_PER_WALL) if v >= min_left]
    rights = [v for v in _weighted_peaks(floor_z, floor_zw, PEAKS_PER_WALL) if v >= min_right]
    fronts = fronts or [max(min_front + 0.5, 3.0)]
    lefts = lefts or [max(min_left + 0.3, 1.5)]
    rights = rights or [max(min_right + 0.3, 1.5)]

    tolerance = EDGE_TOLERANCE_FRAC * math.hypot(*size)
    hypotheses: list[RoomHypothesis] = []
    for front, left, right in itertools.product(fronts, lefts, rights):
        # The ceiling: distances of ceiling lines at height 1 scale with the ceiling height.
        ceilings = [CEILING_PRIOR]
        for coords, weights, dist in (
            (ceil_x, ceil_xw, front),
            (-ceil_z, ceil_zw, left),
            (ceil_z, ceil_zw, right),
        ):
            ok = coords > 0.1
            ceilings += [dist / p for p in _weighted_peaks(coords[ok], weights[ok], 2)]
        for ceiling in ceilings:
            if not 0.3 < ceiling < 3.0:
                continue
            seen = ceiling != CEILING_PRIOR
            hyp = RoomHypothesis(front, left, right, BACK_WALL_PRIOR, ceiling, 0.0, seen)
            score = _edge_score(camera, segments, family, _edges(hyp, to_room), tolerance)
            hypotheses.append(RoomHypothesis(**{**hyp.__dict__, "score": score}))
    hypotheses.sort(key=lambda h: -h.score)
    if evidence is None:
        return hypotheses[0]
    minimum = (min_front, min_left, min_right)
    refined = [
        _refine_by_surfaces(
            h,
            camera,
            segments,
            family,
            to_room,
            tolerance,
            evidence,
            minimum,
            surface_map,
            metres=metres,
        )
        for h in hypotheses[:RESTARTS]
    ]
    best = max(refined, key=lambda h: h.score)
    if surface_map is None:
        return best
    return dataclasses.replace(best, ceiling_seen=surface_map.ceiling_seen)


RESTARTS = 3  # coordinate ascent from the best few line-vote hypotheses
GRID_STEPS = {"front": 28, "left": 24, "right": 24, "ceiling": 20}
ROUNDS = 2
# After the grid (steps of 11% for the front wall, 17% for the side walls), steps of 8%, 4%
# and 2% from the best: on 390 synthetic rooms (seeds 1, 7000-7099, 300000+, 700000+) layout
# IoU +0.40 points (standard error 0.18; 172 rooms better, 146 worse), seen walls nearer the
# truth (front 3.9% -> 3.4% on seed 1). Steps (0.04, 0.02), (0.12, 0.06, 0.03) and down to
# 1% did about as well; interpolating the Surface Network's map to a finer grid added nothing.
FINE_STEPS = (0.08, 0.04, 0.02)
EDGE_WEIGHT = 0.3  # share of the score from line support (the rest: surface colours)
EDGE_NORM = 0.3  # line support is counted in tenths of all segment length
# A weak prior on each wall's distance from the camera (metres, log-normal; converted with the
# camera height the objects tell): it decides walls the photo does not show and breaks ties
# between floor-texture lines. People photograph a room from near one wall, away from the rest.
# The side walls' spread was chosen on 100 synthetic rooms from seeds 500000+ (no test or
# benchmark uses them, but the Surface Network trains on them: tune on 700000+ instead):
# 0.4 gave layout IoU 70.5, 0.6 gave 71.3 (0.3-3 tried); looser, the room's width decides a
# wall out of view more than its own distance.
WALL_DISTANCE_PRIOR = {"front": (4.2, 0.35), "left": (2.2, 0.6), "right": (2.2, 0.6)}
ROOM_WIDTH_PRIOR = (4.4, 0.25)  # metres across, sd of log: one side wall seen places the other
PRIOR_WEIGHT = 0.1
# Agreement with the Surface Network (a share of cells, like colour); with the network from
# 6000 rooms, 9 and 12 scored the same as 6 on 100 rooms from seeds 700000+.
SURFACE_MAP_WEIGHT = 6.0


def _layout_prior(h: RoomHypothesis, metres: float) -> float:
    """Squared log-normal z-scores of the room's width and each wall's distance (metres, with
    the camera `metres` high)."""
    width = (h.left + h.right) * metres
    total = (math.log(width / ROOM_WIDTH_PRIOR[0]) / ROOM_WIDTH_PRIOR[1]) ** 2
    for wall, (median, sd) in WALL_DISTANCE_PRIOR.items():
        total += (math.log(getattr(h, wall) * metres / median) / sd) ** 2
    return total


def _refine_by_surfaces(
    start: RoomHypothesis,
    camera: PinholeCamera,
    segments: Segments,
    family: NDArray[np.int64],
    to_room: FloatArray,
    tolerance: float,
    evidence: SurfaceEvidence,
    minimum: tuple[float, float, float],
    surface_map: SurfaceMap | None = None,
    *,
    metres: float,
) -> RoomHypothesis:
    """Coordinate ascent (`coordinate_search`) over each wall distance and the ceiling,
    scoring surface colour consistency plus line support along the edges (plus agreement with
    the Surface Network's labels when there is a map)."""
    norm = max(float(segments.lengths.sum()), 1.0) * EDGE_NORM

    def score(h: RoomHypothesis) -> float:
        edges = _edge_score(camera, segments, family, _edges(h, to_room), tolerance) / norm
        prior = _layout_prior(h, metres)
        fit = (1 - EDGE_WEIGHT) * evidence.explained(h) + EDGE_WEIGHT * edges
        if surface_map is not None:
            fit += SURFACE_MAP_WEIGHT * surface_map.agreement(
                h.surfaces_seen(surface_map.rays_room)
            )
        return fit - PRIOR_WEIGHT * prior

    grids = {
        "front": np.geomspace(max(minimum[0], 0.8), 14.0, GRID_STEPS["front"]),
        "left": np.geomspace(max(minimum[1], 0.2), 8.0, GRID_STEPS["left"]),
        "right": np.geomspace(max(minimum[2], 0.2), 8.0, GRID_STEPS["right"]),
        "ceiling": np.geomspace(0.5, 2.5, GRID_STEPS["ceiling"]),
    }
    return coordinate_search(start, score, grids)


def coordinate_search(
    start: RoomHypothesis,
    score: Callable[[RoomHypothesis], float],
    grids: dict[str, FloatArray],
) -> RoomHypothesis:
    """The best-scoring room from `start`, one field at a time: every value of the field's
    grid (increasing), for up to ROUNDS rounds; then steps of FINE_STEPS (log) up and down
    from the best, each size until no step helps, never leaving the grid's range. The result
    carries its score."""
    best, best_score = start, score(start)

    def try_value(field: str, value: float) -> bool:
        nonlocal best, best_score
        trial = RoomHypothesis(**{**best.__dict__, field: value, "score": 0.0})
        trial_score = score(trial)
        if trial_score > best_score + 1e-9:
            best, best_score = trial, trial_score
            return True
        return False

    for _ in range(ROUNDS):
        improved = False
        for field, values in grids.items():
            for value in values:
                improved |= try_value(field, float(value))
        if not improved:
            break
    for step in FINE_STEPS:
        improved = True
        while improved:
            improved = False
            for field, values in grids.items():
                for factor in (math.exp(step), math.exp(-step)):
                    value = getattr(best, field) * factor
                    if values[0] <= value <= values[-1]:
                        improved |= try_value(field, value)
    return dataclasses.replace(best, score=best_score)


def _edges(hyp: RoomHypothesis, to_room: FloatArray) -> list[tuple[FloatArray, FloatArray, int]]:
    """World 3D edges of the visible walls with the family of their direction."""
    c = hyp.corners_room() @ to_room.T
    # floor: front (1-2 along z), left (0-1 along x), right (3-2 along x); same for ceiling;
    # vertical corners front-left (1-5) and front-right (2-6).
    return [
        (c[1], c[2], 2), (c[0], c[1], 1), (c[3], c[2], 1),
        (c[5], c[6], 2), (c[4], c[5], 1), (c[7], c[6], 1),
        (c[1], c[5], 0), (c[2], c[6], 0),
    ]  # fmt: skip
