"""Stages and the typed context they read and write.

A stage declares the context slots it requires and the ones it provides. The pipeline
builder checks the chain before anything runs, so a pipeline with an unmet input fails when
it is built, never halfway through a photo.
"""

from __future__ import annotations

from abc import ABC, abstractmethod
from dataclasses import dataclass, field, fields
from typing import Any, ClassVar, TypeVar

import numpy as np
import trimesh
from holiscene_schema import (
    Box3D,
    Camera,
    Layout,
    Mask,
    MaskSource,
    MeshRef,
    RemovedObject,
    SceneObject,
    SupportRelation,
)

from ..core.errors import DomainError
from ..geometry.camera import FloatArray

T = TypeVar("T")


@dataclass
class Detection:
    """One input 2D box with its NYU-40 class (and the name it was imported under)."""

    cls: str
    bbox: tuple[float, float, float, float]
    source_class: str | None = None
    # False when the name was in no vocabulary and became otherprop (the stage warns).
    class_known: bool = True
    # The object's outline when the dataset gave one (source "given"): the masks stages keep it.
    mask: Mask | None = None


@dataclass(frozen=True)
class ObjectMesh:
    """The model chosen for an object, already placed in the world frame."""

    mesh: trimesh.Trimesh
    ref: MeshRef


@dataclass(frozen=True)
class ObjectMask:
    pixels: np.ndarray  # bool (H, W), full image
    source: MaskSource


@dataclass
class SceneContext:
    """Everything a pipeline knows about one photo; stages fill the slots they provide.

    Input slots (always present, possibly empty): image, given_K, detections, depth,
    pinned_supports, pinned_objects, removed_objects.
    """

    image: np.ndarray  # RGB uint8, (H, W, 3)
    given_K: FloatArray | None = None
    detections: list[Detection] | None = None
    # An RGB-D camera's depth along the optical axis, metres, float32 (H, W); 0: no depth.
    depth: np.ndarray | None = None
    # Supports set by people; stages that infer supports must keep them as they are.
    pinned_supports: list[SupportRelation] = field(default_factory=list)
    # Objects people added or changed (SceneObject.set_by_person); the stages that find
    # objects keep them (pipeline/people.py), the masks stage keeps their drawn masks.
    pinned_objects: list[SceneObject] = field(default_factory=list)
    removed_objects: list[RemovedObject] = field(default_factory=list)

    objects: list[SceneObject] | None = None
    intrinsics: tuple[FloatArray, str] | None = None  # K and its source
    masks: dict[str, ObjectMask] | None = None  # by object id
    camera: Camera | None = None
    # The three orthogonal vanishing points (homogeneous image points, rows: vertical first).
    vanishing_points: FloatArray | None = None
    layout: Layout | None = None
    supports: list[SupportRelation] | None = None
    heights: dict[str, float] | None = None  # object id -> metres (single-view metrology)
    boxes_3d: dict[str, Box3D | None] | None = None
    object_meshes: dict[str, ObjectMesh] | None = None
    scene_glb: bytes | None = None
    # Stage name -> what it could not do: stored as the stage's note, marked as a warning.
    notes: dict[str, str] = field(default_factory=dict)
    # Stage name -> what it found that is no problem (e.g. a fit's quality): a plain note.
    reports: dict[str, str] = field(default_factory=dict)
    object_notes: dict[str, str] = field(default_factory=dict)  # object id -> why a value is null
    # Object id -> the chance its 3D box is right (SceneObject.box_3d_confidence), from the
    # stage that judged the box; a box no stage judged has none.
    box_confidences: dict[str, float] = field(default_factory=dict)

    @property
    def height(self) -> int:
        return int(self.image.shape[0])

    @property
    def width(self) -> int:
        return int(self.image.shape[1])


INPUT_SLOTS: frozenset[str] = frozenset(
    {
        "image",
        "given_K",
        "detections",
        "depth",
        "pinned_supports",
        "pinned_objects",
        "removed_objects",
    }
)
SLOTS: frozenset[str] = frozenset(f.name for f in fields(SceneContext)) - {
    "notes",
    "reports",
    "object_notes",
    "box_confidences",
}


def required(value: T | None, slot: str) -> T:
    """The value of a slot a stage declared it requires (the builder guarantees it is set)."""
    if value is None:
        raise StageFailedError(f"slot {slot!r} is empty although the pipeline requires it")
    return value


class PipelineBuildError(DomainError, ValueError):
    """The requested stages cannot form a pipeline (unknown name, unmet input, bad option)."""


class StageFailedError(RuntimeError):
    """A stage could not compute its outputs from this input."""


class Stage(ABC):
    """One step of the pipeline; subclasses register themselves with `@register_stage`."""

    name: ClassVar[str]
    requires: ClassVar[frozenset[str]]
    provides: ClassVar[frozenset[str]]
    # A stage that refines with depth: the pipeline skips it (no run is recorded) for a photo
    # without depth, so the single-photo path is unchanged.
    needs_depth: ClassVar[bool] = False
    # A stage for the single-photo path only (learned on photos without depth): skipped, with
    # no run recorded, for a photo with depth, whose depth stages measure better.
    single_photo_only: ClassVar[bool] = False

    def __init__(self, **options: Any) -> None:
        if options:
            raise PipelineBuildError(f"stage {self.name!r} takes no options, got {sorted(options)}")

    @abstractmethod
    def run(self, ctx: SceneContext) -> None:
        """Read the required slots of `ctx` and set the provided ones."""
