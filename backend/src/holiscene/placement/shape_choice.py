"""Choosing each object's model and its turn in its box by silhouette IoU with the mask.

Candidates are a few variants of the class from the shape library (one per seed) and the
user's models of that class. A box's yaw says nothing about where the object's front is, so
four turns about its vertical axis are tried (the box's depth and width swap on the odd
ones); each candidate is fitted into the box, projected, and its filled triangles compared
with the mask. The turn is chosen with the first library variant, then the model at that turn.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from pathlib import Path

import numpy as np
import trimesh
from holiscene_schema import Box3D, MeshRef, UnknownClassError, normalise_class_name

from ..geometry.camera import FloatArray, rot_y
from ..shapes import GENERIC_CLASSES, MODEL_SUFFIXES, fit_to_box, generate_shape
from ..shapes.user_models import load_model
from .projection import MaskTarget

TURN_MARGIN = 0.005  # IoU a turn must gain over the box's own yaw to be chosen
# Below this many mask pixels the variants of a class look alike: the first one is taken.
MIN_PIXELS_FOR_VARIANTS = 2500


@dataclass(frozen=True)
class UserModel:
    file: str  # relative to the models folder
    mesh: trimesh.Trimesh  # canonical frame (see shapes.user_models)


def load_user_models(folder: Path) -> dict[str, list[UserModel]]:
    """`<folder>/<class>/*.obj|glb|ply` by NYU-40 class, with their relative file names."""
    folder = Path(folder)
    if not folder.is_dir():
        raise FileNotFoundError(f"model folder {folder} does not exist")
    models: dict[str, list[UserModel]] = {}
    for class_dir in sorted(p for p in folder.iterdir() if p.is_dir()):
        if class_dir.name.startswith("."):
            continue
        try:
            cls = normalise_class_name(class_dir.name)
        except UnknownClassError as error:
            raise ValueError(
                f"model folder {class_dir}: {class_dir.name!r} is not an NYU-40 class"
            ) from error
        for path in sorted(class_dir.iterdir()):
            if path.is_file() and path.suffix.lower() in MODEL_SUFFIXES:
                models.setdefault(cls, []).append(
                    UserModel(file=path.relative_to(folder).as_posix(), mesh=load_model(path))
                )
    return models


def placed(mesh: trimesh.Trimesh, centre: FloatArray, yaw_deg: float) -> trimesh.Trimesh:
    transform = np.eye(4)
    transform[:3, :3] = rot_y(math.radians(yaw_deg))
    transform[:3, 3] = centre
    out = mesh.copy()
    out.apply_transform(transform)
    return out


@dataclass(frozen=True)
class FittedModel:
    mesh: trimesh.Trimesh  # world frame
    ref: MeshRef
    yaw_deg: float  # the model's front, as a box yaw
    iou: float


def turns(box: Box3D) -> list[tuple[float, tuple[float, float, float]]]:
    """The box as four (yaw, size): its own, then turned by 90, 180 and 270 degrees."""
    d, h, w = box.size
    return [(box.yaw_deg + 90.0 * k, (d, h, w) if k % 2 == 0 else (w, h, d)) for k in range(4)]


def best_of_turns(scores: list[float]) -> int:
    """The index of the best of four turns' silhouette IoUs; a turn must beat the best so far
    by TURN_MARGIN, so the box's own turn wins ties."""
    best = 0
    for k in range(1, len(scores)):
        if scores[k] > scores[best] + TURN_MARGIN:
            best = k
    return best


def fit_model(
    cls: str,
    box: Box3D,
    target: MaskTarget,
    projection: FloatArray,
    seeds: int = 3,
    user_models: list[UserModel] | None = None,
    mask_pixels: int | None = None,
) -> FittedModel:
    centre = np.array(box.center, dtype=float)
    options = turns(box)

    def score(mesh: trimesh.Trimesh, yaw: float) -> float:
        rotation = rot_y(math.radians(yaw))
        vertices = np.asarray(mesh.vertices, dtype=float) @ rotation.T + centre
        silhouette = target.silhouette(projection, vertices, np.asarray(mesh.faces))
        return target.iou_silhouette(silhouette)

    def library(seed: int, size: tuple[float, float, float]) -> trimesh.Trimesh:
        return generate_shape(cls, size, np.random.default_rng(seed)).mesh

    user_models = user_models or []
    if cls in GENERIC_CLASSES and not user_models:
        yaw, size = options[0]
        mesh = library(0, size)
        return FittedModel(
            placed(mesh, centre, yaw),
            MeshRef(library="builtin", cls=cls, seed=0),
            yaw,
            score(mesh, yaw),
        )
    # The turn, with the first candidate model (stretched to the turned box's size: a
    # proxy, as the model of that size is only built for the chosen turn).
    d, h, w = box.size
    if seeds > 0:
        first_mesh = library(0, (d, h, w))
        first_ref = MeshRef(library="builtin", cls=cls, seed=0)
    else:
        first_mesh = fit_to_box(user_models[0].mesh, (d, h, w))
        first_ref = MeshRef(library="user", cls=cls, file=user_models[0].file)
    stretched = first_mesh.copy()
    stretched.vertices = np.asarray(first_mesh.vertices) * np.array([w / d, 1.0, d / w])
    turn_scores = [score(first_mesh if k % 2 == 0 else stretched, options[k][0]) for k in range(4)]
    best_turn = best_of_turns(turn_scores)
    yaw, size = options[best_turn]
    if best_turn % 2 == 0:
        best = FittedModel(first_mesh, first_ref, yaw, turn_scores[best_turn])
    else:
        mesh = library(0, size) if seeds > 0 else fit_to_box(user_models[0].mesh, size)
        best = FittedModel(mesh, first_ref, yaw, score(mesh, yaw))
    # Then the model at that turn.
    if mask_pixels is not None and mask_pixels < MIN_PIXELS_FOR_VARIANTS:
        seeds = min(seeds, 1)
    candidates: list[tuple[MeshRef, trimesh.Trimesh]] = [
        (MeshRef(library="builtin", cls=cls, seed=seed), library(seed, size))
        for seed in range(1, max(seeds, 0))
    ]
    candidates += [
        (MeshRef(library="user", cls=cls, file=m.file), fit_to_box(m.mesh, size))
        for m in user_models[(0 if seeds > 0 else 1) :]
    ]
    for ref, mesh in candidates:
        value = score(mesh, yaw)
        if value > best.iou:
            best = FittedModel(mesh, ref, yaw, value)
    return FittedModel(placed(best.mesh, centre, yaw), best.ref, yaw, best.iou)
