"""Planning a room: its size, the camera, and where every object stands and on what.

Room frame ("local"): origin on the floor at the room's centre, x along the room's depth
(the camera stands near the wall at -depth/2 and looks towards +x), y up, z across.
Objects are placed against walls, free in the room, on top of other objects' support
surfaces, or on walls. The world frame of the contract is the camera's: see `to_world`.

Supports are ambiguous on purpose: boxes stand on the floor, tables, cabinets and shelves;
books on shelves and desks; bedrooms often hold two night stands of which one has a lamp.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np
import trimesh
from numpy.typing import NDArray

from ..geometry.camera import rot_y
from ..knowledge.object_sizes import MOUNTING_BOTTOM_M
from ..shapes import Shape, generate_shape, typical_size
from . import ranges

FloatArray = NDArray[np.float64]
WALLS = ("far", "left", "right")
WALL_YAW = {"far": 180.0, "left": -90.0, "right": 90.0, "back": 0.0}  # front faces the room


@dataclass
class PlannedObject:
    key: int
    cls: str
    size: FloatArray  # (depth, height, width) in the object's own frame
    center: FloatArray  # room frame
    yaw_deg: float  # room frame
    parent: int | str  # another object's key, or "floor" / "wall"
    support_type: str
    seed: int
    shape: Shape
    looks_like: int | None = None  # another object's key whose material this one shares

    def footprint(self) -> tuple[float, float, float, float]:
        """Axis-aligned (x0, x1, z0, z1) of the object in the room frame."""
        corners = self.room_corners()
        return (corners[:, 0].min(), corners[:, 0].max(), corners[:, 2].min(), corners[:, 2].max())

    def room_corners(self) -> FloatArray:
        half = self.size / 2.0
        signs = np.array([[sx, sy, sz] for sx in (-1, 1) for sy in (-1, 1) for sz in (-1, 1)])
        result: FloatArray = (signs * half) @ rot_y(math.radians(self.yaw_deg)).T + self.center
        return result

    def room_transform(self) -> FloatArray:
        transform = np.eye(4)
        transform[:3, :3] = rot_y(math.radians(self.yaw_deg))
        transform[:3, 3] = self.center
        return transform

    def surfaces(self) -> list[tuple[float, FloatArray, float, float, float]]:
        """Support surfaces in the room frame: (height, centre xz, extent along own x, own z,
        free height above). Extents are in the object's own axes; children keep its yaw."""
        out = []
        for surface in self.shape.support_surfaces:
            (x0, x1), (z0, z1) = surface.x_range, surface.z_range
            local = np.array([(x0 + x1) / 2, surface.y, (z0 + z1) / 2])
            world = rot_y(math.radians(self.yaw_deg)) @ local + self.center
            out.append((float(world[1]), world[[0, 2]], x1 - x0, z1 - z0, surface.clearance))
        return out


@dataclass(frozen=True)
class RoomStyle:
    """Choices that change what rooms hold. The default is the generator every synthetic figure
    in docs/benchmarks.md was measured on; a choice here makes other rooms from the same seeds."""

    # Beds and sofas hold rows of matching cushions against their back (lying or propped up,
    # sometimes a smaller row in front), as people arrange them, instead of a few cushions
    # scattered over the surface.
    cushion_rows: bool = False

    @property
    def folder_suffix(self) -> str:
        """Tells apart rooms of one seed made in different styles (a cache's folder names)."""
        return "-cushion-rows" if self.cushion_rows else ""


DEFAULT_STYLE = RoomStyle()


@dataclass
class RoomPlan:
    depth: float
    width: float
    height: float
    yaw_deg: float  # the room's turn in the camera's world frame
    camera_position: FloatArray  # room frame (x, height above floor, z)
    pitch_deg: float
    roll_deg: float
    hfov_deg: float
    theme: str
    objects: list[PlannedObject] = field(default_factory=list)

    def to_world(self, points: FloatArray) -> FloatArray:
        """Room frame -> the camera-centred world frame (no camera yaw; the room turns)."""
        result: FloatArray = (np.asarray(points) - self.camera_position) @ rot_y(
            math.radians(self.yaw_deg)
        ).T
        return result

    def world_transform(self) -> FloatArray:
        transform = np.eye(4)
        transform[:3, :3] = rot_y(math.radians(self.yaw_deg))
        transform[:3, 3] = -rot_y(math.radians(self.yaw_deg)) @ self.camera_position
        return transform

    def room_mesh(self) -> tuple[trimesh.Trimesh, trimesh.Trimesh, trimesh.Trimesh]:
        """Floor, ceiling and walls (facing inwards) in the room frame."""
        d, h, w = self.depth / 2, self.height, self.width / 2
        floor = _quad([[-d, 0, -w], [-d, 0, w], [d, 0, w], [d, 0, -w]])
        ceiling = _quad([[-d, h, -w], [d, h, -w], [d, h, w], [-d, h, w]])
        walls = _joined(
            [
                _quad([[d, 0, -w], [d, 0, w], [d, h, w], [d, h, -w]]),
                _quad([[-d, 0, w], [-d, 0, -w], [-d, h, -w], [-d, h, w]]),
                _quad([[-d, 0, -w], [d, 0, -w], [d, h, -w], [-d, h, -w]]),
                _quad([[d, 0, w], [-d, 0, w], [-d, h, w], [d, h, w]]),
            ]
        )
        return floor, ceiling, walls


def _joined(quads: list[trimesh.Trimesh]) -> trimesh.Trimesh:
    vertices = np.vstack([q.vertices for q in quads])
    faces = np.vstack([q.faces + 4 * i for i, q in enumerate(quads)])
    return trimesh.Trimesh(vertices=vertices, faces=faces, process=False)


def _quad(points: list[list[float]]) -> trimesh.Trimesh:
    """Two triangles; the vertex order makes the normal face the room's inside."""
    return trimesh.Trimesh(
        vertices=np.array(points, dtype=float),
        faces=np.array([[0, 1, 2], [0, 2, 3]]),
        process=False,
    )


class Planner:
    """Fills a RoomPlan; all randomness comes from one generator, so a seed fixes the room."""

    def __init__(self, rng: np.random.Generator, style: RoomStyle = DEFAULT_STYLE) -> None:
        self.rng = rng
        self.style = style
        self.plan = self._room()
        self._next_key = 0

    # -- room and camera ---------------------------------------------------------------

    def _room(self) -> RoomPlan:
        rng = self.rng
        depth = rng.uniform(*ranges.ROOM_DEPTH_M)
        width = rng.uniform(*ranges.ROOM_WIDTH_M)
        height = rng.uniform(*ranges.ROOM_HEIGHT_M)
        camera = np.array(
            [
                -depth / 2 + rng.uniform(*ranges.CAMERA_BACK_OFFSET_M),
                rng.uniform(*ranges.CAMERA_HEIGHT_M),
                rng.uniform(*ranges.CAMERA_SIDEWAYS_SHARE) * width,
            ]
        )
        return RoomPlan(
            depth=depth,
            width=width,
            height=height,
            yaw_deg=rng.uniform(*ranges.ROOM_YAW_DEG),
            camera_position=camera,
            pitch_deg=rng.uniform(*ranges.CAMERA_PITCH_DEG),
            roll_deg=rng.uniform(*ranges.CAMERA_ROLL_DEG),
            hfov_deg=rng.uniform(*ranges.CAMERA_HFOV_DEG),
            theme=str(rng.choice(list(THEMES))),
        )

    # -- placing -----------------------------------------------------------------------

    def add(
        self,
        cls: str,
        size: FloatArray,
        center: FloatArray,
        yaw: float,
        parent: int | str,
        support_type: str,
        looks_like: int | None = None,
    ) -> PlannedObject:
        seed = int(self.rng.integers(2**31))
        shape = generate_shape(
            cls, (float(size[0]), float(size[1]), float(size[2])), np.random.default_rng(seed)
        )
        obj = PlannedObject(
            self._next_key, cls, size, center, yaw, parent, support_type, seed, shape, looks_like
        )
        self._next_key += 1
        self.plan.objects.append(obj)
        return obj

    def size_of(self, cls: str) -> FloatArray:
        return np.array(typical_size(cls, self.rng), dtype=float)

    def fits(self, footprint: tuple[float, float, float, float], margin: float = 0.05) -> bool:
        """Inside the room, clear of the camera and of every floor object."""
        x0, x1, z0, z1 = footprint
        d, w = self.plan.depth / 2, self.plan.width / 2
        if x0 < -d - 1e-6 or x1 > d + 1e-6 or z0 < -w - 1e-6 or z1 > w + 1e-6:
            return False
        cx, _, cz = self.plan.camera_position
        if x0 - 0.6 < cx < x1 + 0.6 and z0 - 0.6 < cz < z1 + 0.6:
            return False
        for other in self.plan.objects:
            if other.parent == "floor":
                pad = margin
            elif other.cls == "door":
                pad = 0.8  # keep the doorway clear
            else:
                continue
            ox0, ox1, oz0, oz1 = other.footprint()
            if x0 < ox1 + pad and ox0 < x1 + pad and z0 < oz1 + pad and oz0 < z1 + pad:
                return False
        return True

    def collides(self, candidate: PlannedObject) -> bool:
        """Does the candidate's box overlap any placed object's box (room frame)?"""
        lo, hi = candidate.room_corners().min(axis=0), candidate.room_corners().max(axis=0)
        for other in self.plan.objects:
            olo, ohi = other.room_corners().min(axis=0), other.room_corners().max(axis=0)
            if np.all(lo < ohi - 1e-3) and np.all(olo < hi - 1e-3):
                return True
        return False

    def against_wall(
        self, cls: str, wall: str, along: float, size: FloatArray | None = None
    ) -> PlannedObject | None:
        """A floor object with its back to `wall`, centred at `along` on that wall."""
        size = self.size_of(cls) if size is None else size
        center = self._wall_point(wall, along, size[0] / 2 + 0.01, size[1] / 2)
        return self._on_floor(cls, size, center, WALL_YAW[wall])

    def free(
        self, cls: str, x: float, z: float, yaw: float, size: FloatArray | None = None
    ) -> PlannedObject | None:
        size = self.size_of(cls) if size is None else size
        return self._on_floor(cls, size, np.array([x, size[1] / 2, z]), yaw)

    def _on_floor(
        self, cls: str, size: FloatArray, center: FloatArray, yaw: float
    ) -> PlannedObject | None:
        probe = PlannedObject(-1, cls, size, center, yaw, "floor", "below", 0, _EMPTY_SHAPE)
        if not self.fits(probe.footprint()) or self.collides(probe):
            return None
        return self.add(cls, size, center, yaw, "floor", "below")

    def on_wall(
        self, cls: str, wall: str, along: float, bottom: float, size: FloatArray | None = None
    ) -> PlannedObject | None:
        """A flat object hanging on (or set into) a wall, supported from behind."""
        size = self.size_of(cls) if size is None else size
        if bottom + size[1] > self.plan.height - 0.05:
            return None
        center = self._wall_point(wall, along, size[0] / 2 + 0.005, bottom + size[1] / 2)
        probe = PlannedObject(
            -1, cls, size, center, WALL_YAW[wall], "wall", "behind", 0, _EMPTY_SHAPE
        )
        if self.collides(probe):
            return None
        half_wall = (self.plan.width if wall in ("far", "back") else self.plan.depth) / 2
        if abs(along) + size[2] / 2 > half_wall - 0.02:
            return None
        return self.add(cls, size, center, WALL_YAW[wall], "wall", "behind")

    def on_top(
        self, parent: PlannedObject, cls: str, surface_index: int | None = None
    ) -> PlannedObject | None:
        """Put an object on one of the parent's support surfaces, if it fits there."""
        surfaces = parent.surfaces()
        if not surfaces:
            return None
        index = int(self.rng.integers(len(surfaces))) if surface_index is None else surface_index
        top, centre, extent_x, extent_z, clearance = surfaces[index]
        size = self.size_of(cls)
        # Shrink to the surface (and under the next shelf) rather than give up.
        size[0] = min(size[0], extent_x * 0.9)
        size[2] = min(size[2], extent_z * 0.9)
        size[1] = min(size[1], clearance * 0.85)
        if min(size) < 0.03:
            return None
        slack_x, slack_z = (extent_x - size[0]) / 2, (extent_z - size[2]) / 2
        offset_local = np.array(
            [self.rng.uniform(-slack_x, slack_x), 0.0, self.rng.uniform(-slack_z, slack_z)]
        )
        center = _on_surface(parent, top, centre, offset_local, size)
        for sibling in self.plan.objects:
            same_surface = (
                sibling.parent == parent.key and abs(sibling.center[1] - center[1]) < 0.05
            )
            gap = np.linalg.norm((sibling.center - center)[[0, 2]])
            if same_surface and gap < (max(sibling.size[[0, 2]]) + max(size[[0, 2]])) / 2:
                return None
        return self.add(cls, size, center, parent.yaw_deg, parent.key, "below")

    def at_back_of(
        self,
        parent: PlannedObject,
        surface_index: int,
        cls: str,
        size: FloatArray,
        inset: float,
        along: float,
        looks_like: int | None = None,
    ) -> PlannedObject:
        """`cls` of `size` on a support surface of `parent`, `inset` from the surface's back
        edge (the parent's own -x: a bed's headboard, a sofa's back), `along` its width from
        the middle. The caller has sized and spaced it to fit."""
        top, centre, extent_x, _, _ = parent.surfaces()[surface_index]
        offset_local = np.array([-extent_x / 2 + inset + size[0] / 2, 0.0, along])
        center = _on_surface(parent, top, centre, offset_local, size)
        return self.add(cls, size, center, parent.yaw_deg, parent.key, "below", looks_like)

    def _wall_point(self, wall: str, along: float, off_wall: float, height: float) -> FloatArray:
        d, w = self.plan.depth / 2, self.plan.width / 2
        if wall == "far":
            return np.array([d - off_wall, height, along])
        if wall == "back":
            return np.array([-d + off_wall, height, along])
        if wall == "left":
            return np.array([along, height, -w + off_wall])
        return np.array([along, height, w - off_wall])

    def wall_length(self, wall: str) -> float:
        return self.plan.width if wall in ("far", "back") else self.plan.depth


def _on_surface(
    parent: PlannedObject,
    top: float,
    centre: FloatArray,
    offset_local: FloatArray,
    size: FloatArray,
) -> FloatArray:
    """The room-frame centre of an object of `size` resting on a surface of `parent` (its
    height and centre from `parent.surfaces()`), moved by `offset_local` in the parent's axes."""
    offset = rot_y(math.radians(parent.yaw_deg)) @ offset_local
    result: FloatArray = np.array([centre[0], top + size[1] / 2 + 0.002, centre[1]]) + offset
    return result


# Stand-in shape of the probe objects used to test a placement before building the real one.
_EMPTY_SHAPE = Shape(
    mesh=trimesh.Trimesh(), parts=[], face_part=np.zeros(0, dtype=np.int32), support_surfaces=[]
)


# -- themes --------------------------------------------------------------------------------
# Each theme places its anchor furniture, then the shared steps decorate the room.


def _against_some_wall(
    p: Planner, cls: str, size: FloatArray, tries: int = 8, far_first: bool = False
) -> PlannedObject | None:
    """Stand an anchor piece against a random wall at a random spot, trying a few times
    (the far wall, which the camera faces, first when `far_first`)."""
    for attempt in range(tries):
        far = far_first and attempt < 3
        wall = "far" if far else str(p.rng.choice(WALLS, p=[0.5, 0.25, 0.25]))
        slack = max(0.0, p.wall_length(wall) / 2 - size[2] / 2 - 0.1)
        placed = p.against_wall(cls, wall, p.rng.uniform(-slack, slack), size)
        if placed is not None:
            return placed
    return None


def _wall_of(obj: PlannedObject) -> str:
    return next(wall for wall, yaw in WALL_YAW.items() if yaw == obj.yaw_deg)


def _along_wall(obj: PlannedObject) -> float:
    return float(obj.center[2] if _wall_of(obj) in ("far", "back") else obj.center[0])


def _bedroom(p: Planner) -> None:
    bed_size = p.size_of("bed")
    bed = _against_some_wall(p, "bed", bed_size, far_first=True)
    if bed is not None:
        wall, along = _wall_of(bed), _along_wall(bed)
        if p.style.cushion_rows:
            _cushion_rows(p, bed, first_row=(1, 2, 2, 2, 3, 4), scale=1.0)
        else:
            for _ in range(int(p.rng.integers(1, 4))):
                p.on_top(bed, "pillow")
        stand_size = p.size_of("night_stand")
        for side in (-1, 1):
            if p.rng.random() < 0.85:
                offset = along + side * (bed_size[2] / 2 + stand_size[2] / 2 + 0.05)
                stand = p.against_wall("night_stand", wall, offset, stand_size.copy())
                if stand is not None:
                    _decorate(p, stand)
        top = bed_size[1] + p.rng.uniform(0.4, 0.7)
        p.on_wall("picture", wall, along + p.rng.uniform(-0.3, 0.3), top)
    _floor_lamp(p)
    _fill_walls(p, ["dresser", "cabinet", "night_stand", "bookshelf", "desk", "box", "chair"])


def _cushion_rows(
    p: Planner, parent: PlannedObject, first_row: tuple[int, ...], scale: float
) -> None:
    """Cushions in a row against the parent's back, as many as `first_row` draws, and on a
    third of them a smaller row in front; `scale` sizes them (a sofa's are smaller)."""
    surfaces = parent.shape.support_surfaces
    if not surfaces:
        return
    back = min(range(len(surfaces)), key=lambda i: surfaces[i].x_range[0])
    depth = _cushion_row(p, parent, back, int(p.rng.choice(first_row)), 0.0, scale)
    if depth > 0 and p.rng.random() < 0.35:
        _cushion_row(p, parent, back, int(p.rng.integers(1, 4)), depth, 0.7 * scale)


def _cushion_row(
    p: Planner,
    parent: PlannedObject,
    surface_index: int,
    count: int,
    inset: float,
    scale: float,
) -> float:
    """`count` matching cushions (one size, one material) side by side across a surface,
    `inset` from its back edge, propped up (thin and tall) or lying; returns the row's depth
    (0 if none fit)."""
    _, _, extent_x, extent_z, clearance = parent.surfaces()[surface_index]
    if count < 1:
        return 0.0
    gap = p.rng.uniform(0.0, 0.04)
    width = min(p.rng.uniform(0.45, 0.75) * scale, (0.95 * extent_z - gap * (count - 1)) / count)
    if p.rng.random() < 0.5:  # propped against the back
        size = np.array([p.rng.uniform(0.12, 0.2), p.rng.uniform(0.3, 0.5) * scale, width])
    else:
        size = np.array([p.rng.uniform(0.3, 0.5) * scale, p.rng.uniform(0.1, 0.2), width])
    size[1] = min(size[1], 0.85 * clearance)
    if width < 0.15 * scale or inset + size[0] > 0.9 * extent_x:
        return 0.0
    first: int | None = None
    for along in (np.arange(count) - (count - 1) / 2) * (width + gap):
        cushion = p.at_back_of(
            parent, surface_index, "pillow", size.copy(), inset, float(along), first
        )
        first = cushion.key if first is None else first
    return float(size[0])


def _living(p: Planner) -> None:
    sofa = _against_some_wall(p, "sofa", p.size_of("sofa"))
    if sofa is not None:
        if p.style.cushion_rows:
            _cushion_rows(p, sofa, first_row=(0, 1, 2, 2, 3), scale=0.7)
        else:
            for _ in range(int(p.rng.integers(0, 4))):
                p.on_top(sofa, "pillow")
        inward = -rot_y(math.radians(sofa.yaw_deg)) @ np.array([-1.0, 0.0, 0.0])
        spot = sofa.center + inward * (sofa.size[0] / 2 + 0.6)
        table = p.free(
            "table",
            spot[0],
            spot[2],
            sofa.yaw_deg,
            np.array([0.6, 0.45, 1.0]) * p.rng.uniform(0.8, 1.2, 3),
        )
        if table is not None:
            _decorate(p, table)
        for side in (-1, 1):  # side tables: two of a kind, one maybe with a lamp
            if p.rng.random() < 0.6:
                offset = _along_wall(sofa) + side * (sofa.size[2] / 2 + 0.3)
                side_table = p.against_wall(
                    "table", _wall_of(sofa), offset, np.array([0.45, 0.55, 0.45])
                )
                if side_table is not None:
                    _decorate(p, side_table)
    _floor_lamp(p)
    _fill_walls(p, ["cabinet", "bookshelf", "shelves", "dresser", "chair", "table", "box"])


def _office(p: Planner) -> None:
    for wall in p.rng.permutation(WALLS)[: int(p.rng.integers(1, 3))]:
        desk = p.against_wall("desk", str(wall), p.rng.uniform(-1.0, 1.0))
        if desk is None:
            continue
        if p.rng.random() < 0.7:
            p.on_top(desk, "television")
        _decorate(p, desk)
        inward = rot_y(math.radians(desk.yaw_deg)) @ np.array([1.0, 0.0, 0.0])
        spot = desk.center + inward * (desk.size[0] / 2 + 0.35)
        p.free("chair", spot[0], spot[2], desk.yaw_deg + 180.0)
    _fill_walls(p, ["bookshelf", "shelves", "cabinet", "cabinet", "box", "table"])


def _dining(p: Planner) -> None:
    cx = p.rng.uniform(0.0, 0.25) * p.plan.depth
    table = p.free("table", cx, p.rng.uniform(-0.3, 0.3), 90.0 * int(p.rng.integers(2)))
    if table is not None:
        _decorate(p, table)
        x0, x1, z0, z1 = table.footprint()
        mid_x, mid_z = (x0 + x1) / 2, (z0 + z1) / 2
        seats = [
            (x0 - 0.35, mid_z, 0.0),
            (x1 + 0.35, mid_z, 180.0),
            (mid_x, z0 - 0.35, -90.0),
            (mid_x, z1 + 0.35, 90.0),
        ]
        for x, z, yaw in seats:
            if p.rng.random() < 0.8:
                p.free("chair", x, z, yaw)
    _fill_walls(p, ["cabinet", "counter", "shelves", "dresser", "refrigerator", "box"])


def _kitchen(p: Planner) -> None:
    wall = str(p.rng.choice(WALLS))
    counter = p.against_wall(
        "counter", wall, p.rng.uniform(-0.5, 0.5), p.size_of("counter") * [1, 1, 1.4]
    )
    if counter is not None:
        if p.rng.random() < 0.6:
            p.on_top(counter, "sink")
        _decorate(p, counter)
    _fill_walls(p, ["refrigerator", "cabinet", "counter", "table", "shelves", "box"])


THEMES = {
    "bedroom": _bedroom,
    "living": _living,
    "office": _office,
    "dining": _dining,
    "kitchen": _kitchen,
}

# What may stand on what: (child class, weight) per supporter class. Each support surface
# gets up to three tries, each filled with this probability.
SURFACE_FILL = 0.7
DECORATIONS: dict[str, list[tuple[str, float]]] = {
    "night_stand": [("lamp", 0.6), ("books", 0.2), ("box", 0.2)],
    "dresser": [("lamp", 0.3), ("television", 0.2), ("box", 0.3), ("books", 0.2), ("mirror", 0.1)],
    "cabinet": [("box", 0.45), ("television", 0.15), ("lamp", 0.2), ("books", 0.2)],
    "bookshelf": [("books", 0.75), ("box", 0.25)],
    "shelves": [("books", 0.55), ("box", 0.45)],
    "table": [("lamp", 0.25), ("books", 0.4), ("box", 0.35)],
    "desk": [("books", 0.45), ("box", 0.25), ("lamp", 0.3)],
    "counter": [("box", 0.6), ("books", 0.2), ("lamp", 0.2)],
}


def _fill_walls(p: Planner, candidates: list[str]) -> None:
    """Walk along the walls, standing furniture where it fits, then decorate it."""
    for wall in WALLS:
        length = p.wall_length(wall)
        along = -length / 2 + p.rng.uniform(0.1, 0.8)
        while along < length / 2 - 0.3:
            cls = str(p.rng.choice(candidates))
            size = p.size_of(cls)
            centre = along + size[2] / 2
            placed = p.against_wall(cls, wall, centre, size) if p.rng.random() < 0.9 else None
            if placed is not None:
                _decorate(p, placed)
            along = centre + size[2] / 2 + p.rng.uniform(0.05, 0.6)


def _decorate(p: Planner, obj: PlannedObject) -> None:
    choices = DECORATIONS.get(obj.cls)
    if not choices:
        return
    classes = [cls for cls, _ in choices]
    weights = np.array([w for _, w in choices]) / sum(w for _, w in choices)
    for index, _ in enumerate(obj.surfaces()):
        for _ in range(3):
            if p.rng.random() < SURFACE_FILL:
                p.on_top(obj, str(p.rng.choice(classes, p=weights)), index)


def _floor_lamp(p: Planner) -> None:
    """A standing lamp, so that lamps are not always on furniture."""
    if p.rng.random() < 0.4:
        d, w = p.plan.depth / 2, p.plan.width / 2
        size = np.array([0.4, p.rng.uniform(1.3, 1.7), 0.4])
        p.free("lamp", p.rng.uniform(0.0, d - 0.3), p.rng.choice([-w + 0.3, w - 0.3]), 0.0, size)


def _wall_items(p: Planner) -> None:
    """Door, windows with curtains, pictures, mirrors and televisions on walls."""
    door_wall = str(p.rng.choice(("left", "right", "far")))
    half = p.wall_length(door_wall) / 2
    if p.rng.random() < 0.6:
        p.on_wall("door", door_wall, p.rng.uniform(-half + 0.6, half - 0.6), 0.0)
    for wall in WALLS:
        half = p.wall_length(wall) / 2
        if p.rng.random() < 0.3:
            size = p.size_of("window")
            along = p.rng.uniform(-half + size[2], half - size[2]) if half > size[2] else 0.0
            sill = p.rng.uniform(*MOUNTING_BOTTOM_M["window"])
            window = p.on_wall("window", wall, along, sill, size)
            if window is not None and p.rng.random() < 0.6:
                for side in (-1, 1):
                    curtain_size = np.array([0.08, p.plan.height - 0.15, p.rng.uniform(0.35, 0.6)])
                    p.on_wall(
                        "curtain",
                        wall,
                        along + side * (size[2] / 2 + curtain_size[2] / 2 - 0.1),
                        0.02,
                        curtain_size,
                    )
        for cls, probability in (
            ("picture", 0.45),
            ("picture", 0.2),
            ("mirror", 0.12),
            ("television", 0.12),
        ):
            if p.rng.random() < probability:
                size = p.size_of(cls)
                along = p.rng.uniform(-half + 0.4, half - 0.4)
                p.on_wall(cls, wall, along, p.rng.uniform(*MOUNTING_BOTTOM_M[cls]), size)


def _floor_boxes(p: Planner) -> None:
    for _ in range(int(p.rng.integers(0, 3))):
        d, w = p.plan.depth / 2, p.plan.width / 2
        p.free(
            "box",
            p.rng.uniform(-d + 0.8, d - 0.3),
            p.rng.uniform(-w + 0.3, w - 0.3),
            float(p.rng.uniform(-30, 30)),
        )


def plan_room(rng: np.random.Generator, style: RoomStyle = DEFAULT_STYLE) -> RoomPlan:
    planner = Planner(rng, style)
    _wall_items(planner)  # doors and windows first, so furniture does not block them
    THEMES[planner.plan.theme](planner)
    _floor_boxes(planner)
    return planner.plan
