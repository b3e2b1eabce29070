"""Synthetic scenes run through metrology, placement and model fitting (cached per seed)."""

from __future__ import annotations

import math
from dataclasses import dataclass
from functools import cache

import cv2
import numpy as np
from holiscene.geometry.camera import rot_y
from holiscene.pipeline.base import SceneContext
from holiscene.pipeline.stages.metrology import HeightsByMetrology
from holiscene.pipeline.stages.placement import PlacementStage
from holiscene.placement.oracle import MaskKind, context_from_truth
from holiscene.placement.projection import MaskTarget
from holiscene.placement.room import pinhole, projection_matrix
from holiscene.placement.solver import Placement
from holiscene.segmentation.rle import decode_mask
from holiscene.shapes import generate_shape
from holiscene.synth.generate import SyntheticScene, synthesize
from holiscene_schema import SceneObject

SEEDS = range(3000, 3011)


@cache
def scene(seed: int) -> SyntheticScene:
    return synthesize(seed)


@dataclass(frozen=True)
class Placed:
    synthetic: SyntheticScene
    ctx: SceneContext
    details: dict[str, Placement]


@cache
def placed(seed: int, masks: MaskKind = "truth") -> Placed:
    ctx = context_from_truth(scene(seed), masks)
    HeightsByMetrology().run(ctx)
    stage = PlacementStage()
    stage.run(ctx)
    return Placed(scene(seed), ctx, dict(stage.last))


_VISIBLE: dict[tuple[str, str], float] = {}


def visible_fraction(synthetic: SyntheticScene, obj: SceneObject) -> float:
    """How much of the object's true silhouette its mask shows (1 = fully visible)."""
    key = (synthetic.name, obj.id)
    if key not in _VISIBLE:
        _VISIBLE[key] = _visible_fraction(synthetic, obj)
    return _VISIBLE[key]


def _visible_fraction(synthetic: SyntheticScene, obj: SceneObject) -> float:
    assert obj.box_3d is not None and obj.mesh is not None and obj.mask is not None
    assert synthetic.truth.camera is not None
    camera = pinhole(synthetic.truth.camera)
    assert camera is not None
    box = obj.box_3d
    shape = generate_shape(obj.cls, tuple(box.size), np.random.default_rng(obj.mesh.seed))
    vertices = np.asarray(shape.mesh.vertices) @ rot_y(math.radians(box.yaw_deg)).T + box.center
    width, height = synthetic.truth.image.width, synthetic.truth.image.height
    mask = decode_mask(obj.mask, width, height)
    pixels = vertices @ projection_matrix(camera).T
    pixels = pixels[:, :2] / pixels[:, 2:]
    if np.any(pixels < 0) or np.any(pixels[:, 0] >= width) or np.any(pixels[:, 1] >= height):
        return 0.0  # partly outside the photo
    whole = MaskTarget(np.ones_like(mask), max_side=10**6)
    silhouette = whole.silhouette(
        projection_matrix(camera), vertices, np.asarray(shape.mesh.faces)
    ).astype(np.uint8)
    inner = cv2.erode(silhouette, np.ones((3, 3), np.uint8)).astype(bool)
    return float((mask & inner).sum() / max(int(inner.sum()), 1))
