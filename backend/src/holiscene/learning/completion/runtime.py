"""Shape completion at run time (onnxruntime, no PyTorch): an object's observed depth points in,
its completed mesh in world coordinates out.

The observed points are the object's mask pixels with depth, back-projected with the camera
(`placement.depth_box.object_points`) and moved into the normalised frame of the object's 3D
box (points well outside the box are another object's and dropped). The network completes
them; the grown points and the observed ones are meshed (`meshing.py`) and the mesh is placed
back with the box.
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
from ..budget import single_thread_session
from .meshing import mesh_from_points
from .scans import KEEP_BOUND, PARTIAL_POINTS, resample

MODEL_DIR = Path(__file__).resolve().parents[1] / "completion_model"
MIN_OBSERVED_POINTS = 150


def to_box_frame(points: NDArray[np.float64], box: Box3D) -> NDArray[np.float64]:
    """World points in the box's normalised frame (the box is [-0.5, 0.5]^3)."""
    local = (points - np.asarray(box.center)) @ rot_y(math.radians(box.yaw_deg))
    result: NDArray[np.float64] = local / np.asarray(box.size)
    return result


def _world_from_box(box: Box3D) -> NDArray[np.float64]:
    """The 4x4 transform from the box's normalised frame to the world."""
    transform = np.eye(4)
    transform[:3, :3] = rot_y(math.radians(box.yaw_deg)) @ np.diag(box.size)
    transform[:3, 3] = box.center
    return transform


def from_box_frame(mesh: trimesh.Trimesh, box: Box3D) -> trimesh.Trimesh:
    out = mesh.copy()
    out.apply_transform(_world_from_box(box))
    return out


def points_from_box_frame(points: NDArray[np.floating], box: Box3D) -> NDArray[np.float64]:
    """Normalised box-frame points (N, 3) in the world: `to_box_frame` undone."""
    transform = _world_from_box(box)
    result: NDArray[np.float64] = np.asarray(points, dtype=float) @ transform[:3, :3].T
    return result + transform[:3, 3]


@dataclass(frozen=True)
class Completion:
    mesh: trimesh.Trimesh  # world frame
    observed: int  # points the network read (before resampling)


class ShapeCompleter:
    def __init__(self, model_dir: Path = MODEL_DIR) -> None:
        metadata = json.loads((model_dir / "metadata.json").read_text())
        self.session = single_thread_session(model_dir / metadata["model"])
        self.grown = int(metadata["skeleton_points"]) * int(metadata["grown_per_skeleton"])

    def complete_normalised(self, partial: NDArray[np.floating]) -> NDArray[np.float32]:
        """Completed points (grown, then the observed ones) of PARTIAL_POINTS normalised points."""
        batch = np.asarray(partial, dtype=np.float32)[None]
        completed: NDArray[np.float32] = self.session.run(["completed"], {"partial": batch})[0][0]
        return completed

    def complete_in_box(
        self, world_points: NDArray[np.float64], box: Box3D
    ) -> tuple[NDArray[np.float32], int] | None:
        """The network's completed points in the box's normalised frame and how many observed
        points it read, or None when too few lie in the box."""
        local = to_box_frame(world_points, box)
        local = local[np.abs(local).max(axis=1) <= KEEP_BOUND]
        if len(local) < MIN_OBSERVED_POINTS:
            return None
        partial = resample(local, PARTIAL_POINTS, np.random.default_rng(0))
        return self.complete_normalised(partial), len(local)

    def complete_points(
        self, world_points: NDArray[np.float64], box: Box3D
    ) -> NDArray[np.float64] | None:
        """The completed points in the world frame (before meshing), or None as `complete`."""
        done = self.complete_in_box(world_points, box)
        return None if done is None else points_from_box_frame(done[0], box)

    def complete(self, world_points: NDArray[np.float64], box: Box3D) -> Completion | None:
        """The completed mesh of observed points, or None when too few lie in the box."""
        done = self.complete_in_box(world_points, box)
        if done is None:
            return None
        completed, observed = done
        return Completion(from_box_frame(mesh_from_points(completed), box), observed)


@lru_cache(maxsize=2)
def completer(model_dir: Path = MODEL_DIR) -> ShapeCompleter:
    return ShapeCompleter(model_dir)
