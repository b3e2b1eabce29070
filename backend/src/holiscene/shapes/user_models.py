"""User models: a folder of meshes per class, brought into the canonical frame.

Layout: `<folder>/<class>/*.obj|*.glb|*.ply`, one sub-folder per class. Folder names are
normalised like any class name ("Night Stand", "nightstand" and "night_stand" all mean
night_stand); a folder that names no NYU-40 class is an error, not silently skipped, since
its models would otherwise never be used. Other files (an OBJ's .mtl, textures, notes) are
ignored.

Models must be y up. Their front may face another horizontal axis (`front`); they are
turned to face +x, re-centred on their bounding box and scaled uniformly so their largest
side is 1 m: their proportions are kept for choosing a model by aspect, and `fit_to_box`
(or `shape_from_mesh`) stretches one into an object's box.
"""

from __future__ import annotations

import math
from pathlib import Path
from typing import Literal

import numpy as np
import trimesh
from holiscene_schema import UnknownClassError, normalise_class_name

from .fitting import fit_to_box
from .shape import Shape

MODEL_SUFFIXES: tuple[str, ...] = (".obj", ".glb", ".ply")
FrontAxis = Literal["+x", "-x", "+z", "-z"]

# Turn about +y that takes each front direction onto +x.
_TURN_DEG: dict[str, float] = {"+x": 0.0, "+z": 90.0, "-x": 180.0, "-z": -90.0}


def load_model_folder(folder: Path, front: FrontAxis = "+x") -> dict[str, list[trimesh.Trimesh]]:
    """Every model under `folder`, by NYU-40 class, in the canonical frame (sorted by file
    name; classes without models are left out)."""
    folder = Path(folder)
    if not folder.is_dir():
        raise FileNotFoundError(f"model folder {folder} does not exist")
    models: dict[str, list[trimesh.Trimesh]] = {}
    for class_dir in sorted(
        p for p in folder.iterdir() if p.is_dir() and not p.name.startswith(".")
    ):
        try:
            cls = normalise_class_name(class_dir.name)
        except UnknownClassError as error:
            raise ValueError(
                f"model folder {class_dir}: {class_dir.name!r} is not an NYU-40 class or a "
                "known alias; rename it (e.g. 'chair', 'night_stand')"
            ) from error
        files = sorted(
            f for f in class_dir.iterdir() if f.is_file() and f.suffix.lower() in MODEL_SUFFIXES
        )
        for path in files:
            models.setdefault(cls, []).append(load_model(path, front))
    return models


def load_model(path: Path, front: FrontAxis = "+x") -> trimesh.Trimesh:
    """One model file as a single mesh in the canonical frame (see the module docstring)."""
    loaded = trimesh.load(path, force="mesh")
    if not isinstance(loaded, trimesh.Trimesh) or len(loaded.faces) == 0:
        raise ValueError(f"model {path}: no triangles found")
    loaded.apply_transform(
        trimesh.transformations.rotation_matrix(math.radians(_TURN_DEG[front]), [0.0, 1.0, 0.0])
    )
    extents = np.asarray(loaded.extents, dtype=float)
    # Keep proportions; an axis along which the model is flat stays flat.
    size = np.where(extents > 0, extents / extents.max(), 1.0)
    return fit_to_box(loaded, tuple(size))


def shape_from_mesh(mesh: trimesh.Trimesh, size: tuple[float, float, float]) -> Shape:
    """A user model as a `Shape` filling the box of `size`: one part, no support surfaces
    (nothing is known about its tops)."""
    fitted = fit_to_box(mesh, size)
    return Shape(
        mesh=fitted,
        parts=["model"],
        face_part=np.zeros(len(fitted.faces), dtype=np.int32),
        support_surfaces=[],
    )
