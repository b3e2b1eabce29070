"""3D boxes that best explain the masks under the support constraints (thesis Eq. 4.4-4.6).

For each object, from the floor up, a few discrete choices are searched (orientations aligned
with the room or its supporter, which wall or which face of the supporter it hangs on), and
for each the box's position and size maximise IoU(projected box, mask):

- Supported from below (Eq. 4.5): the bottom rests on the supporter's top surface, or on the
  floor; the centre stays over the supporter's footprint. For supporters with surfaces inside
  their box (shelves, a mattress below a headboard, a seat), the resting height is searched
  too, between the supporter's bottom and top.
- Supported from behind (Eq. 4.6): the back is on a wall of the layout (or on a side face of
  the supporting object's box), the centre within that rectangle, the box facing out of it.
- Hanging from the ceiling: the top touches the ceiling.

The search is DIRECT over the bounds, then BOBYQA from its best point.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass, field
from functools import cached_property

import numpy as np
from holiscene_schema import Box3D, SceneObject, SupportRelation

from ..geometry.camera import FloatArray, PinholeCamera
from ..pipeline.stages.boxes import box_on_plane
from ..shapes import SIZE_RANGES
from .optimise import maximise
from .projection import MaskTarget, box_corners_fast, box_hull, convex_hull_mask
from .room import UP, Rect, Room, box_faces, front_of, projection_matrix, wrap_deg, yaw_of

# Supporters whose support surfaces may lie inside their box (library shapes: shelves, beds,
# sofas, chairs, counters, cabinets and night stands with open rows).
INNER_SURFACE_CLASSES = frozenset(
    {"bed", "sofa", "chair", "bookshelf", "shelves", "counter", "cabinet", "night_stand"}
)
OFF_AXIS_MARGIN = 0.03  # IoU a yaw off the room's axes must gain to be preferred
WALL_PENALTY = 2.0  # objective per metre of box outside the room (or off its wall)


@dataclass(frozen=True)
class Pose:
    centre: FloatArray
    size: FloatArray  # (depth, height, width) along the box's own axes
    yaw_deg: float

    @cached_property
    def corners(self) -> FloatArray:
        yaw = math.radians(self.yaw_deg)
        return box_corners_fast(self.centre, self.size, (math.cos(yaw), math.sin(yaw)))

    def box(self) -> Box3D:
        return Box3D(
            center=[round(float(v), 4) for v in self.centre],
            size=[round(float(v), 4) for v in self.size],
            yaw_deg=round(wrap_deg(self.yaw_deg), 3),
        )


@dataclass
class Candidate:
    """One discrete choice with its continuous parameters x -> pose."""

    label: str
    build: Callable[[FloatArray], Pose]
    x0: FloatArray
    lo: FloatArray
    hi: FloatArray
    penalty: Callable[[Pose], float] = lambda pose: 0.0
    handicap: float = 0.0
    rest: Callable[[FloatArray], float | None] = lambda x: None


@dataclass(frozen=True)
class Placement:
    box: Box3D
    iou_initial: float  # IoU of the initial box of the first choice
    iou: float
    surface: str  # what it rests on or hangs from
    rest_y: float | None = None  # the resting plane of the bottom (supported from below)
    score_initial: float = math.nan  # IoU less the penalties (outside the room, off a wall)
    score: float = math.nan


@dataclass
class PlacementOptions:
    global_evals: int = 80
    local_evals: int = 60
    max_side: int = 80  # pixels of the longer side of the IoU window
    height_slack: float = 0.35  # the measured height may change by this fraction
    off_axis_yaws: tuple[float, ...] = (45.0,)
    # Compare boxes with the mask's convex hull (a box's projection is convex; chair legs
    # and table tops leave gaps in a mask that would make the best box too small).
    convex_masks: bool = True


def _size_bounds(cls: str) -> tuple[tuple[float, float], tuple[float, float], FloatArray]:
    """Horizontal size bounds (either axis), height bounds, and the typical size."""
    ranges = SIZE_RANGES.get(cls)
    if ranges is None:
        return (0.1, 1.5), (0.1, 2.0), np.array([0.5, 0.5, 0.5])
    lo = min(ranges.depth[0], ranges.width[0]) * 0.7
    hi = max(ranges.depth[1], ranges.width[1]) * 1.3
    typical = np.array([sum(r) / 2.0 for r in (ranges.depth, ranges.height, ranges.width)])
    return (lo, hi), (ranges.height[0] * 0.7, ranges.height[1] * 1.3), typical


def _mask_bbox(mask: np.ndarray) -> list[float]:
    rows, cols = np.flatnonzero(mask.any(axis=1)), np.flatnonzero(mask.any(axis=0))
    return [float(cols[0]), float(rows[0]), float(cols[-1] + 1), float(rows[-1] + 1)]


def _no_penalty(pose: Pose) -> float:
    return 0.0


@dataclass(frozen=True)
class _RestFrame:
    """Where a standing object may rest: its supporter's top (or inner levels) or the floor.

    Positions are searched in the frame's horizontal axes (its front, then its side) around
    its centre, within `half` of it; `rest_lo`..`rest_hi` is the range of resting heights.
    """

    label: str
    yaw: float
    centre: FloatArray
    half: FloatArray
    rest_lo: float
    rest_hi: float
    yaws: list[float]  # orientations to try, the frame's own first
    on_floor: bool  # kept inside the room (the floor); a supporter's footprint bounds it instead

    @property
    def searches_rest(self) -> bool:
        return self.rest_hi - self.rest_lo > 1e-3

    @cached_property
    def axes(self) -> tuple[FloatArray, FloatArray]:
        front = front_of(self.yaw)
        rot = np.array([front, [0.0, 0.0, 0.0], np.cross(front, UP)])
        return rot[0], rot[2]

    def local(self, point: FloatArray) -> FloatArray:
        axis_a, axis_b = self.axes
        return np.array([(point - self.centre) @ axis_a, (point - self.centre) @ axis_b])

    def rest_of(self, x: FloatArray) -> float | None:
        return float(x[5]) if self.searches_rest else self.rest_hi

    def builder(self, yaw: float) -> Callable[[FloatArray], Pose]:
        """x = (front, side, depth, width, height[, resting height]) -> the pose at `yaw`."""
        axis_a, axis_b = self.axes

        def build(x: FloatArray) -> Pose:
            rest_y = float(x[5]) if self.searches_rest else self.rest_hi
            centre = self.centre + axis_a * x[0] + axis_b * x[1]
            centre = np.array([centre[0], rest_y + x[4] / 2.0, centre[2]])
            return Pose(centre, np.array([x[2], x[4], x[3]]), yaw)

        return build


@dataclass
class Placer:
    """Places objects one after the other; supporters must be placed before what they hold."""

    camera: PinholeCamera
    room: Room | None
    floor_y: float
    classes: dict[str, str]  # object id -> class, for every object of the scene
    options: PlacementOptions = field(default_factory=PlacementOptions)
    placed: dict[str, Placement] = field(default_factory=dict)

    def __post_init__(self) -> None:
        self.projection = projection_matrix(self.camera)
        self.optical_axis = self.camera.world_from_cv[:, 2].copy()

    # -- scoring -------------------------------------------------------------------------

    def iou(self, target: MaskTarget, pose: Pose) -> float:
        return target.iou_polygon(box_hull(self.projection, pose.corners, self.optical_axis))

    def ray(self, pixel: FloatArray) -> FloatArray:
        direction = np.linalg.solve(self.projection, np.array([pixel[0], pixel[1], 1.0]))
        result: FloatArray = direction / np.linalg.norm(direction)
        return result

    # -- one object ------------------------------------------------------------------------

    def place(
        self, obj: SceneObject, mask: np.ndarray, support: SupportRelation | None, height: float
    ) -> Placement | str:
        """The placement, or the reason there is none."""
        if not mask.any():
            return "its mask is empty"
        if self.options.convex_masks:
            mask = convex_hull_mask(mask)
        target = MaskTarget(mask, max_side=self.options.max_side)
        parent = support.parent if support is not None else "floor"
        kind = support.type if support is not None else "below"
        if kind == "below" and parent != "ceiling":
            candidates = self._standing(obj, mask, parent, height)
        elif parent == "ceiling":
            candidates = self._hanging(obj, mask, height)
        else:
            candidates = self._attached(obj, mask, parent, height)
        if isinstance(candidates, str):
            return candidates
        best: tuple[float, Candidate, FloatArray, float] | None = None
        iou_initial = score_initial = math.nan
        for candidate in candidates:

            def objective(x: FloatArray, c: Candidate = candidate) -> float:
                pose = c.build(x)
                return self.iou(target, pose) - c.penalty(pose)

            optimum = maximise(
                objective,
                candidate.x0,
                candidate.lo,
                candidate.hi,
                self.options.global_evals,
                self.options.local_evals,
            )
            if math.isnan(iou_initial):
                iou_initial = self.iou(target, candidate.build(candidate.x0))
                score_initial = optimum.initial_value
            score = optimum.value - candidate.handicap
            if best is None or score > best[0]:
                best = (score, candidate, optimum.x, optimum.value)
        if best is None:
            return "no placement to try"
        _, chosen, x, value = best
        pose = chosen.build(x)
        placement = Placement(
            box=pose.box(),
            iou_initial=iou_initial,
            iou=self.iou(target, pose),
            surface=chosen.label,
            rest_y=chosen.rest(x),
            score_initial=score_initial,
            score=value,
        )
        self.placed[obj.id] = placement
        return placement

    # -- supported from below --------------------------------------------------------------

    def _initial_box(
        self, obj: SceneObject, mask: np.ndarray, plane_y: float
    ) -> tuple[FloatArray, float] | None:
        """Centre (on the plane) and visible width of a box whose bottom edge is the mask's."""
        probe = obj.model_copy(update={"bbox": _mask_bbox(mask)})
        box = box_on_plane(self.camera, probe, plane_y)
        if box is None:
            return None
        centre = np.array(box.center)
        centre[1] = plane_y
        # A bottom edge hidden behind something in front reads as a contact far away, even
        # beyond the walls: pull such a box back along its viewing direction into the room.
        pull = self._inside_room_fraction(centre)
        return centre * np.array([pull, 1.0, pull]), float(box.size[2]) * pull

    def _inside_room_fraction(self, point: FloatArray, margin: float = 0.2) -> float:
        """The largest s <= 1 that keeps (s x, y, s z) inside the room's footprint."""
        if self.room is None:
            return 1.0
        half = self.room.size[[0, 2]] / 2.0 - margin
        local = self.room.to_local(np.array([point[0], self.room.centre[1], point[2]]))[0]
        camera = self.room.to_local(np.array([0.0, self.room.centre[1], 0.0]))[0]
        fraction = 1.0
        for axis, bound in ((0, half[0]), (2, half[1])):
            step = local[axis] - camera[axis]
            limit = bound if step > 0 else -bound
            if abs(local[axis]) > bound and abs(step) > 1e-9:
                fraction = min(fraction, (limit - camera[axis]) / step)
        return float(max(fraction, 0.05))

    def _standing(
        self, obj: SceneObject, mask: np.ndarray, parent: str, height: float
    ) -> list[Candidate] | str:
        (size_lo, size_hi), (h_lo, h_hi), typical = _size_bounds(obj.cls)
        slack = self.options.height_slack
        h_bounds = (max(h_lo, height * (1 - slack)), min(h_hi, height * (1 + slack)))
        if h_bounds[0] >= h_bounds[1]:
            h_bounds = (height * (1 - slack), height * (1 + slack))
        frame = self._rest_frame(parent)
        if isinstance(frame, str):
            return frame
        start = self._standing_start(obj, mask, frame, typical)
        if isinstance(start, str):
            return start
        centre0, width0, rest0 = start
        local0 = frame.local(centre0)
        scale = float(np.clip(width0 / max(typical[2], 1e-3), 0.5, 2.0))
        d0 = float(np.clip(typical[0] * scale, size_lo, size_hi))
        w0 = float(np.clip(width0, size_lo, size_hi))
        if frame.on_floor:
            radius = max(0.5, 1.0 * max(d0, w0))
            lo_ab = np.maximum(local0 - radius, -frame.half + 0.02)
            hi_ab = np.minimum(local0 + radius, frame.half - 0.02)
        else:
            lo_ab, hi_ab = -frame.half, frame.half
        local0 = np.clip(local0, lo_ab, hi_ab)

        x0 = [local0[0], local0[1], d0, w0, float(np.clip(height, *h_bounds))]
        lo = [lo_ab[0], lo_ab[1], size_lo, size_lo, h_bounds[0]]
        hi = [hi_ab[0], hi_ab[1], size_hi, size_hi, h_bounds[1]]
        if frame.searches_rest:
            x0.append(rest0)
            lo.append(frame.rest_lo)
            hi.append(frame.rest_hi)
        penalty = self._outside_room_penalty() if frame.on_floor else _no_penalty
        out = []
        for index, yaw in enumerate(frame.yaws):
            aligned = index == 0 or (
                self.room is not None and abs(wrap_deg(yaw - self.room.yaw_deg, 90.0)) < 5.0
            )
            out.append(
                Candidate(
                    label=frame.label,
                    build=frame.builder(yaw),
                    x0=np.array(x0),
                    lo=np.array(lo),
                    hi=np.array(hi),
                    penalty=penalty,
                    handicap=0.0 if aligned else OFF_AXIS_MARGIN,
                    rest=frame.rest_of,
                )
            )
        return out

    def _rest_frame(self, parent: str) -> _RestFrame | str:
        """The surface a standing object rests on: its placed supporter's, or the floor."""
        if parent in self.placed:
            support = self.placed[parent].box
            s_centre, s_size, s_yaw = (
                np.array(support.center),
                np.array(support.size),
                support.yaw_deg,
            )
            top = float(s_centre[1] + s_size[1] / 2.0)
            bottom = float(s_centre[1] - s_size[1] / 2.0)
            inner = self.classes.get(parent, "") in INNER_SURFACE_CLASSES
            yaws = [s_yaw]
            if self.room is not None and abs(wrap_deg(s_yaw - self.room.yaw_deg, 90.0)) > 5.0:
                yaws.append(self.room.yaw_deg)
            return _RestFrame(
                label=f"on {parent}",
                yaw=s_yaw,
                centre=s_centre,
                half=s_size[[0, 2]] / 2.0,
                rest_lo=bottom + 0.05 * s_size[1] if inner else top,
                rest_hi=top,
                yaws=yaws,
                on_floor=False,
            )
        if parent in self.classes:
            return f"its supporter {parent} has no 3D box"
        # The floor (or a structural parent).
        if self.room is not None:
            frame_yaw, frame_centre = self.room.yaw_deg, self.room.centre
            half = self.room.size[[0, 2]] / 2.0
        else:
            frame_yaw, frame_centre, half = 0.0, np.zeros(3), np.array([30.0, 30.0])
        return _RestFrame(
            label="floor",
            yaw=frame_yaw,
            centre=frame_centre,
            half=half,
            rest_lo=self.floor_y,
            rest_hi=self.floor_y,
            yaws=[frame_yaw] + [frame_yaw + a for a in self.options.off_axis_yaws],
            on_floor=True,
        )

    def _standing_start(
        self, obj: SceneObject, mask: np.ndarray, frame: _RestFrame, typical: FloatArray
    ) -> tuple[FloatArray, float, float] | str:
        """Initial centre, visible width and resting height, or why there is none.

        The top of the supporter is tried first, then lower levels of an inner surface; an
        object on a supporter whose bottom edge meets no level starts at the supporter's centre.
        """
        rest0 = frame.rest_hi
        init = self._initial_box(obj, mask, rest0)
        if init is None and frame.rest_lo < frame.rest_hi:
            for level in np.linspace(frame.rest_hi, frame.rest_lo, 8)[1:]:
                init = self._initial_box(obj, mask, float(level))
                if init is not None:
                    rest0 = float(level)
                    break
        if init is None:
            if frame.on_floor:
                return "no 3D box: its bottom edge does not meet the floor in view"
            init = (frame.centre.copy(), float(typical[2]))
        return init[0], init[1], rest0

    def _outside_room_penalty(self) -> Callable[[Pose], float]:
        """Objective lost by a box whose footprint leaves the room."""
        if self.room is None:
            return _no_penalty
        room_centre, room_rotation = self.room.centre, self.room.rotation
        room_half = self.room.size[[0, 2]] / 2.0

        def outside_room(pose: Pose) -> float:
            local = (pose.corners[:4] - room_centre) @ room_rotation
            over = np.maximum(np.abs(local[:, [0, 2]]) - room_half, 0.0)
            return WALL_PENALTY * float(over.sum()) / 4.0

        return outside_room

    def _hanging(self, obj: SceneObject, mask: np.ndarray, height: float) -> list[Candidate] | str:
        if self.room is None:
            return "no 3D box: hanging from the ceiling needs the room layout"
        (size_lo, size_hi), _, typical = _size_bounds(obj.cls)
        ceiling = self.room.ceiling_y
        bbox = _mask_bbox(mask)
        ray = self.ray(np.array([(bbox[0] + bbox[2]) / 2.0, (bbox[1] + bbox[3]) / 2.0]))
        if ray[1] <= 1e-6:
            return "no 3D box: it hangs from a ceiling out of view"
        centre0 = ray * ((ceiling - height / 2.0) / ray[1])
        frame_yaw, half = self.room.yaw_deg, self.room.size[[0, 2]] / 2.0
        axis_a, axis_b = front_of(frame_yaw), np.cross(front_of(frame_yaw), UP)
        rel = centre0 - self.room.centre
        local0 = np.clip(np.array([rel @ axis_a, rel @ axis_b]), -half, half)
        slack = self.options.height_slack

        def build(x: FloatArray) -> Pose:
            centre = self.room.centre + axis_a * x[0] + axis_b * x[1] if self.room else x[:3]
            centre = np.array([centre[0], ceiling - x[4] / 2.0, centre[2]])
            return Pose(centre, np.array([x[2], x[4], x[3]]), frame_yaw)

        x0 = np.array([local0[0], local0[1], typical[0], typical[2], height])
        lo = np.array([-half[0], -half[1], size_lo, size_lo, height * (1 - slack)])
        hi = np.array([half[0], half[1], size_hi, size_hi, height * (1 + slack)])
        return [Candidate("ceiling", build, x0, lo, hi)]

    # -- supported from behind -------------------------------------------------------------

    def _attached(
        self, obj: SceneObject, mask: np.ndarray, parent: str, height: float
    ) -> list[Candidate] | str:
        bbox = _mask_bbox(mask)
        mid_y = (bbox[1] + bbox[3]) / 2.0
        probes = [
            np.array([(bbox[0] + bbox[2]) / 2.0, mid_y]),
            np.array([bbox[0] + 1.0, mid_y]),
            np.array([bbox[2] - 1.0, mid_y]),
        ]
        rects: list[Rect] = []
        if parent in self.placed:
            box = self.placed[parent].box
            for face in box_faces(np.array(box.center), np.array(box.size), box.yaw_deg):
                if float(face.normal @ (-face.centre)) > 0:  # faces the camera
                    rects.append(face)
            label_of = {r.name: f"{r.name} face of {parent}" for r in rects}
        elif parent in self.classes:
            return f"its supporter {parent} has no 3D box"
        else:
            if self.room is None:
                return "no 3D box: objects on walls need the room layout"
            for pixel in probes:
                walls = self.room.walls_by_ray(self.ray(pixel))
                if walls and all(walls[0].name != r.name for r in rects):
                    rects.append(walls[0])
            label_of = {r.name: r.name for r in rects}
        if not rects:
            return "no 3D box: no wall or face behind it in view"
        return [
            c
            for c in (
                self._on_rect(obj, probes, rect, label_of[rect.name], height) for rect in rects
            )
            if c is not None
        ]

    def _on_rect(
        self, obj: SceneObject, probes: list[FloatArray], rect: Rect, label: str, height: float
    ) -> Candidate | None:
        (size_lo, size_hi), _, typical = _size_bounds(obj.cls)
        thickness = float(np.clip(typical[0], 0.01, 0.6))
        hits = []
        for pixel in probes:
            ray = self.ray(pixel)
            t = rect.hit(ray)
            if t is not None:
                hits.append(ray * t)
        if not hits:
            return None
        tangent = rect.tangent
        along0 = float((hits[0] - rect.centre) @ tangent)
        alt0 = float(hits[0][1])
        width0 = (
            abs(float((hits[-1] - hits[-2]) @ tangent)) if len(hits) == 3 else float(typical[2])
        )
        slack = self.options.height_slack
        h_bounds = (height * (1 - slack), height * (1 + slack))
        L = rect.half_length
        yaw = yaw_of(rect.normal)

        def build(x: FloatArray) -> Pose:
            centre = rect.centre + tangent * x[0] + rect.normal * (thickness / 2.0)
            centre = np.array([centre[0], x[1], centre[2]])
            return Pose(centre, np.array([thickness, x[3], x[2]]), yaw)

        def off_rect(pose: Pose) -> float:
            half_w, half_h = float(pose.size[2]) / 2.0, float(pose.size[1]) / 2.0
            centre_y = float(pose.centre[1])
            along = float((pose.centre - rect.centre) @ tangent)
            over = (
                max(0.0, abs(along) + half_w - L)
                + max(0.0, centre_y + half_h - rect.y_max)
                + max(0.0, rect.y_min - (centre_y - half_h))
            )
            return WALL_PENALTY * over

        x0 = np.array(
            [
                np.clip(along0, -L, L),
                np.clip(alt0, rect.y_min, rect.y_max),
                np.clip(width0, size_lo, size_hi),
                np.clip(height, *h_bounds),
            ]
        )
        lo = np.array([-L, rect.y_min, size_lo, h_bounds[0]])
        hi = np.array([L, rect.y_max, size_hi, h_bounds[1]])
        return Candidate(label, build, x0, lo, hi, penalty=off_rect)
