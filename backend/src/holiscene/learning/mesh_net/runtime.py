"""The mesh network at run time (onnxruntime, no PyTorch): an object's class, 3D box and mask
in, its mesh in world coordinates out.

A box's yaw does not say where the object's front is: of the four quarter turns of the box (its
depth and width swap on the odd ones), the one whose template's silhouette best matches the mask
is chosen, as the library fit chooses its turn (`placement.shape_choice`), and the network runs
once, in that turn. Faces whose vertices the network expects to stay far from the true
surface are cut (at the threshold chosen on validation views, never more than half the faces).
The result fills its box, as a library model does, so the viewers can tell it belongs there.
"""

from __future__ import annotations

import json
import math
from dataclasses import dataclass
from functools import lru_cache
from pathlib import Path

import numpy as np
import trimesh
from holiscene_schema import Box3D
from numpy.typing import NDArray

from ...geometry.camera import rot_y
from ...placement.projection import MaskTarget
from ...placement.shape_choice import best_of_turns, turns
from ...shapes import fit_to_box
from ..budget import single_thread_session
from .inputs import condition_vector, silhouette_input, template, view_direction

MODEL_DIR = Path(__file__).resolve().parents[1] / "mesh_net_model"


@dataclass(frozen=True)
class GeneratedMesh:
    mesh: trimesh.Trimesh  # world frame
    yaw_deg: float  # the turn chosen: the model's front, as a box yaw
    iou: float  # silhouette IoU with the mask
    faces_cut: int  # by the topology modification


def cut_faces(
    faces: NDArray[np.int64], vertex_error: NDArray[np.floating], threshold: float, min_kept: float
) -> NDArray[np.int64]:
    """The faces whose vertices are all expected within `threshold` of the truth; when that
    would cut more than 1 - min_kept of them, the better half (by worst vertex) is kept."""
    face_error = np.asarray(vertex_error, dtype=float)[faces].max(axis=1)
    keep = face_error <= threshold
    if keep.mean() < min_kept:
        keep = face_error <= np.quantile(face_error, 1.0 - min_kept)
    result: NDArray[np.int64] = faces[keep]
    return result


class MeshGenerator:
    def __init__(self, model_dir: Path = MODEL_DIR) -> None:
        metadata = json.loads((model_dir / "metadata.json").read_text())
        self.session = single_thread_session(model_dir / metadata["model"])
        self.classes = frozenset(metadata["classes"])
        threshold = metadata["cut_threshold"]  # null: no face is cut
        self.cut_threshold = math.inf if threshold is None else float(threshold)
        self.min_kept = float(metadata["min_kept"])

    def deform(
        self,
        cls: str,
        size: tuple[float, float, float],
        silhouette: NDArray[np.float32],
        direction: NDArray[np.float64],
    ) -> trimesh.Trimesh:
        """The moved and cut template in the box's local frame (metres, centred, unturned),
        stretched to fill the box exactly as every library model does (`shapes.fit_to_box`)."""
        shape = template(cls, size)
        moved, error = self.session.run(
            ["vertices", "error"],
            {
                "silhouette": silhouette[None],
                "condition": condition_vector(cls, size, direction)[None],
                "template": shape.vertices[None],
            },
        )
        scale = np.asarray(size, dtype=float)
        # An error threshold in the eval frame: the box's longest side is 1.
        faces = cut_faces(shape.faces, error[0] * scale.max(), self.cut_threshold, self.min_kept)
        mesh = trimesh.Trimesh(moved[0] * scale, faces, process=False)
        mesh.remove_unreferenced_vertices()
        return fit_to_box(mesh, size)

    def generate(
        self, cls: str, box: Box3D, mask: NDArray[np.bool_], projection: NDArray[np.float64]
    ) -> GeneratedMesh | None:
        """The object's mesh (None for a class the network was not trained on)."""
        if cls not in self.classes or not mask.any():
            return None
        target = MaskTarget(mask, max_side=96)
        centre = np.asarray(box.center, dtype=float)

        def placed(
            local: NDArray[np.floating], faces: NDArray[np.int64], yaw: float
        ) -> tuple[NDArray[np.float64], float]:
            world = np.asarray(local, dtype=float) @ rot_y(math.radians(yaw)).T + centre
            return world, target.iou_silhouette(target.silhouette(projection, world, faces))

        # The turn is chosen with the template itself, as the library fit chooses it with its
        # first variant: the network bends any template towards the mask, which would make
        # every turn look alike.
        options = turns(box)
        scores = []
        for yaw, size in options:
            shape = template(cls, size)
            scores.append(placed(shape.positions * np.asarray(size), shape.faces, yaw)[1])
        yaw, size = options[best_of_turns(scores)]
        direction = view_direction(np.zeros(3), centre, yaw)
        local = self.deform(cls, size, silhouette_input(mask), direction)
        faces = np.asarray(local.faces)
        world, iou = placed(np.asarray(local.vertices), faces, yaw)
        mesh = trimesh.Trimesh(world, faces, process=False)
        return GeneratedMesh(mesh, yaw, iou, len(template(cls, size).faces) - len(faces))


@lru_cache(maxsize=2)
def mesh_generator(model_dir: Path = MODEL_DIR) -> MeshGenerator:
    return MeshGenerator(model_dir)
