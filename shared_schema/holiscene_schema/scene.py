"""The scene: what the pipeline computes from one photo and what annotators correct.

Conventions (see docs/architecture.md, "Conventions"):
- World frame: origin at the camera centre, y up, x horizontal forward, z right; metres.
- A 3D box has a centre, a size along its own axes (x front, y up, z right before yaw) and a
  yaw in degrees about world +y (right-handed: yaw 90 turns the box's front from +x to -z).
  `corners_3d` lists the same box as 8 world points in the order of `BOX_CORNER_SIGNS`.
- Unknown values are null; a note says why.
"""

from __future__ import annotations

from datetime import datetime
from typing import Annotated, Literal

from pydantic import BaseModel, ConfigDict, Field, model_validator

from .classes import Nyu40Class
from .support_graph import support_graph_problems

Point2 = Annotated[list[float], Field(min_length=2, max_length=2)]
Point3 = Annotated[list[float], Field(min_length=3, max_length=3)]
Matrix3 = Annotated[list[Point3], Field(min_length=3, max_length=3)]
BoxCorners = Annotated[list[Point3], Field(min_length=8, max_length=8)]
Box2D = Annotated[list[float], Field(min_length=4, max_length=4, description="[x1, y1, x2, y2]")]

# Corner order of every 3D box: (sign of local x, y, z) half-sizes; bottom face then top face.
BOX_CORNER_SIGNS: tuple[tuple[int, int, int], ...] = (
    (-1, -1, -1), (1, -1, -1), (1, -1, 1), (-1, -1, 1),
    (-1, 1, -1), (1, 1, -1), (1, 1, 1), (-1, 1, 1),
)  # fmt: skip

SupportType = Literal["below", "behind"]
StructuralParent = Literal["floor", "wall", "ceiling"]


class SchemaModel(BaseModel):
    """Base of every contract model: strict field names, aliases used on the wire."""

    model_config = ConfigDict(
        extra="forbid",
        validate_by_name=True,
        validate_by_alias=True,
        serialize_by_alias=True,
        # Fields with defaults are always present in what we send, so generated types
        # mark them required (e.g. an edit's `kind`, which tells edit types apart).
        json_schema_serialization_defaults_required=True,
    )


class ImageInfo(SchemaModel):
    file: str = Field(description="File name of the photo, relative to the scene's folder")
    width: int = Field(gt=0)
    height: int = Field(gt=0)


# Where a camera's height came from: a prior, estimated from the photo, set by hand, the
# dataset's ground truth, or measured from the depth's floor plane.
HeightSource = Literal["prior", "estimated", "manual", "ground_truth", "depth"]


class Camera(SchemaModel):
    K: Matrix3 = Field(description="3x3 intrinsics, pixels")
    K_source: Literal["given", "assumed", "estimated"]
    pitch_deg: float | None = Field(
        description="Angle of the optical axis below the horizon (positive looking down)"
    )
    roll_deg: float | None = Field(
        description="Rotation about the optical axis (positive: camera turned clockwise as "
        "seen from behind it, so the scene appears turned counter-clockwise)"
    )
    height_m: float | None = Field(default=None, description="Camera centre above the floor")
    height_source: HeightSource | None = Field(
        default=None,
        description="Where height_m came from: a prior, estimated from the photo, set by hand, "
        "the dataset's ground truth, or measured from the depth's floor plane",
    )
    note: str | None = None


class Layout(SchemaModel):
    corners_2d: Annotated[list[Point2 | None], Field(min_length=8, max_length=8)] | None = Field(
        default=None,
        description="Room cuboid corners in the image, order of corners_3d; null for a corner "
        "behind the camera (it has no image point)",
    )
    corners_3d: BoxCorners | None = None
    source: Literal["estimated", "manual", "ground_truth"] | None = None
    note: str | None = None


MaskSource = Literal["given", "box", "grabcut", "model", "ground_truth", "manual"]


class Mask(SchemaModel):
    """A binary mask inside a window of the image, run-length encoded row by row.

    `rle` alternates runs of 0 and 1 pixels, starting with a (possibly empty) run of 0.
    """

    origin: Annotated[list[int], Field(min_length=2, max_length=2)] = Field(
        description="[x, y] of the window's top-left pixel"
    )
    size: Annotated[list[int], Field(min_length=2, max_length=2)] = Field(
        description="[width, height] of the window"
    )
    rle: list[Annotated[int, Field(ge=0)]]
    source: MaskSource

    @model_validator(mode="after")
    def _runs_fill_window(self) -> Mask:
        if sum(self.rle) != self.size[0] * self.size[1]:
            raise ValueError("mask runs do not add up to the window's pixel count")
        return self


class Box3D(SchemaModel):
    center: Point3
    size: Point3 = Field(description="Extent along the box's own x (front), y (up), z axes")
    yaw_deg: float


class MeshRef(SchemaModel):
    """Where an object's mesh comes from: the built-in library (class + seed), a file,
    `completion`: completed from the object's depth points, or `learned`: the class template
    deformed by the mesh network (those two meshes are only in the GLB)."""

    library: Literal["builtin", "user", "completion", "learned"]
    cls: str = Field(alias="class")
    seed: int | None = None
    file: str | None = None


class DepthRef(SchemaModel):
    file: str = Field(description="16-bit PNG beside the scene file; 0 = no depth")
    metres_per_unit: float = Field(gt=0)


class SceneObject(SchemaModel):
    id: str = Field(min_length=1, max_length=64, pattern=r"^[A-Za-z0-9_-]+$")
    cls: Nyu40Class = Field(alias="class")
    source_class: str | None = Field(
        default=None, description="The class name as imported, before mapping to NYU-40"
    )
    bbox: Box2D
    mask: Mask | None = None
    box_3d: Box3D | None = None
    corners_3d: BoxCorners | None = None
    box_3d_confidence: float | None = Field(
        default=None,
        ge=0.0,
        le=1.0,
        description="How likely the 3D box is right: the box refiner's estimate of the chance "
        "that it overlaps the true box at 3D IoU 0.15 or more; null where no model judged it",
    )
    mesh: MeshRef | None = None
    score: float | None = Field(default=None, ge=0.0, le=1.0, description="Detection confidence")
    source: Literal["given", "detector", "manual"] | None = Field(
        default=None,
        description="Where the object came from: boxes given with the photo, the object "
        "detector, or a person; null in scenes stored before sources were recorded",
    )
    set_by_person: list[Literal["object", "class", "bbox", "mask"]] = Field(
        default_factory=list,
        description="What people set: 'object' when a person added it (drawn, or a detector "
        "suggestion accepted), and its class, box or mask when a person changed them. A "
        "pipeline re-run keeps all of these.",
    )
    note: str | None = None


class SupportRelation(SchemaModel):
    child: str
    parent: str = Field(description="An object id, or 'floor', 'wall' or 'ceiling'")
    type: SupportType
    source: Literal["auto", "manual"]
    confidence: float | None = Field(default=None, ge=0.0, le=1.0)
    author: str | None = None
    time: datetime | None = None


class StageRun(SchemaModel):
    name: str
    seconds: float = Field(ge=0.0)
    note: str | None = None
    warning: bool = Field(
        default=False,
        description="The note tells what the stage could not do (shown as a warning), "
        "not just what it found",
    )
    model: str | None = Field(
        default=None,
        description="The learned model the stage ran, as the server's model registry names "
        "it (e.g. 'Relation Network v2'); None for stages without one, or runs outside a "
        "server",
    )


class RemovedObject(SchemaModel):
    """An object a person removed: a pipeline re-run does not bring it back (an object it
    finds overlapping this box is taken as the same one)."""

    id: str
    cls: Nyu40Class = Field(alias="class")
    bbox: Box2D


class Scene(SchemaModel):
    schema_version: Literal[1] = 1
    name: str
    image: ImageInfo
    camera: Camera | None = None
    layout: Layout = Field(default_factory=Layout)
    depth: DepthRef | None = Field(default=None, description="Depth along the optical axis")
    objects: list[SceneObject] = Field(default_factory=list)
    supports: list[SupportRelation] = Field(default_factory=list)
    removed_by_person: list[RemovedObject] = Field(
        default_factory=list, description="Objects people removed; a re-run leaves them out"
    )
    stages: list[StageRun] = Field(
        default_factory=list, description="Pipeline stages that produced this scene"
    )

    @model_validator(mode="after")
    def _consistent(self) -> Scene:
        ids = [o.id for o in self.objects]
        if len(set(ids)) != len(ids):
            raise ValueError("object ids must be unique")
        problems = support_graph_problems(ids, [(s.child, s.parent) for s in self.supports])
        if problems:
            raise ValueError("; ".join(problems))
        return self
