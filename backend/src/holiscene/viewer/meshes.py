"""Each object's mesh for the viewer, from the most faithful source that fits its box.

1. The scene's GLB (`scene.glb` beside a scene.json, or the stored scene's): one node per
   object, named by its id, in world coordinates; it is what the pipeline fitted (the model
   and its turn in the box, which a MeshRef does not record). A node is used only while it
   still fills the object's current box, so a GLB older than the scene is not trusted.
2. The object's MeshRef: a built-in library model rebuilt from (class, seed) and fitted into
   the box with the box's yaw as its front (exact for synthetic ground truth), or a user
   model file from the models folder.
3. The box itself.
Objects without a 3D box are not drawn.
"""

from __future__ import annotations

import io
import logging
import math
from dataclasses import dataclass
from pathlib import Path
from typing import Literal

import numpy as np
import trimesh
from holiscene_schema import Scene, SceneObject, UnknownClassError
from numpy.typing import NDArray

from ..geometry.camera import FloatArray, rot_y
from ..shapes import fit_to_box, generate_shape
from ..shapes.user_models import load_model
from .geometry import object_corners

log = logging.getLogger(__name__)

MeshSource = Literal["scene.glb", "library", "user model", "box"]

# A GLB node fills its object's box when their bounds agree to this (metres + fraction).
FIT_TOLERANCE_M = 0.02
FIT_TOLERANCE_FRACTION = 0.02


@dataclass(frozen=True)
class ObjectMesh:
    vertices: NDArray[np.float32]  # (N, 3) world frame
    faces: NDArray[np.int32]  # (M, 3)
    source: MeshSource


@dataclass(frozen=True)
class MeshPlan:
    meshes: dict[str, ObjectMesh]
    notes: list[str]


def glb_object_meshes(glb: bytes) -> dict[str, trimesh.Trimesh]:
    """The GLB's meshes by node name, in world coordinates (room nodes included)."""
    loaded = trimesh.load(io.BytesIO(glb), file_type="glb", force="scene")
    if not isinstance(loaded, trimesh.Scene):
        raise ValueError("not a glTF scene")
    out: dict[str, trimesh.Trimesh] = {}
    for node in loaded.graph.nodes_geometry:
        transform, geometry_name = loaded.graph[node]
        geometry = loaded.geometry.get(geometry_name)
        if isinstance(geometry, trimesh.Trimesh) and len(geometry.faces):
            out[str(node)] = geometry.copy().apply_transform(transform)
    return out


def fills_box(vertices: FloatArray, corners: FloatArray, inside_only: bool = False) -> bool:
    """Whether a mesh's bounds in the box's own frame are the box's (within tolerance), or with
    `inside_only` lie within them (a completed mesh reaches only as far as its points).

    In the box's frame, not the world's: a fitted model touches each face of its box but
    not necessarily its corners, so turned by a yaw its world bounds are smaller."""
    origin = corners[0]
    # Box axes from the contract's corner order: 0->1 is local x, 0->4 is y, 0->3 is z.
    edges = np.stack([corners[1] - origin, corners[4] - origin, corners[3] - origin])
    lengths = np.linalg.norm(edges, axis=1)
    if np.any(lengths < 1e-9):
        return False
    local = (np.asarray(vertices, dtype=float) - origin) @ (edges / lengths[:, None]).T
    tolerance = FIT_TOLERANCE_M + FIT_TOLERANCE_FRACTION * float(lengths.max())
    low, high = local.min(axis=0), local.max(axis=0) - lengths
    if inside_only:
        return bool(np.all(low >= -tolerance) and np.all(high <= tolerance))
    return bool(np.abs(low).max() <= tolerance and np.abs(high).max() <= tolerance)


def _placed(mesh: trimesh.Trimesh, obj: SceneObject) -> trimesh.Trimesh:
    assert obj.box_3d is not None
    transform = np.eye(4)
    transform[:3, :3] = rot_y(math.radians(obj.box_3d.yaw_deg))
    transform[:3, 3] = obj.box_3d.center
    return mesh.copy().apply_transform(transform)


def _from_mesh_ref(obj: SceneObject, models_dir: Path | None) -> tuple[trimesh.Trimesh, str]:
    """The MeshRef's model in the object's box; raises ValueError when it cannot be built."""
    ref = obj.mesh
    if ref is None or obj.box_3d is None:
        raise ValueError("no mesh reference")
    size = (float(obj.box_3d.size[0]), float(obj.box_3d.size[1]), float(obj.box_3d.size[2]))
    if ref.library == "builtin":
        try:
            shape = generate_shape(ref.cls, size, np.random.default_rng(ref.seed or 0))
        except UnknownClassError as exc:
            raise ValueError(str(exc)) from exc
        return _placed(shape.mesh, obj), "library"
    if ref.library in ("completion", "learned"):
        raise ValueError(f"a {ref.library} mesh is kept only in the scene's GLB")
    if ref.file is None or models_dir is None:
        raise ValueError(f"user model {ref.file!r}: no models folder given")
    path = models_dir / ref.file
    if not path.is_file():
        raise ValueError(f"user model {path} not found")
    return _placed(fit_to_box(load_model(path), size), obj), "user model"


# The 12 outward triangles of a box whose corners are in BOX_CORNER_SIGNS order (bottom face
# 0-3, the top 4-7 above them), so a box needs no convex hull (and no SciPy).
_BOX_FACES = np.array(
    [[0, 1, 2], [0, 2, 3], [4, 6, 5], [4, 7, 6]]
    + [[i, i + 4, (i + 1) % 4 + 4] for i in range(4)]
    + [[i, (i + 1) % 4 + 4, (i + 1) % 4] for i in range(4)]
)


def _box_mesh(corners: FloatArray) -> trimesh.Trimesh:
    return trimesh.Trimesh(
        vertices=np.asarray(corners, dtype=float), faces=_BOX_FACES, process=False
    )


def object_meshes(scene: Scene, glb: bytes | None, models_dir: Path | None = None) -> MeshPlan:
    notes: list[str] = []
    from_glb: dict[str, trimesh.Trimesh] = {}
    if glb is not None:
        try:
            from_glb = glb_object_meshes(glb)
        except Exception as exc:  # a broken file must not stop the viewer: boxes remain
            log.warning("scene GLB unreadable: %s", exc)
            notes.append(f"the scene's GLB could not be read ({type(exc).__name__}); boxes shown")
    meshes: dict[str, ObjectMesh] = {}
    stale: list[str] = []
    for obj in scene.objects:
        corners = object_corners(obj)
        if corners is None:
            continue
        mesh: trimesh.Trimesh | None = None
        source: MeshSource = "box"
        candidate = from_glb.get(obj.id)
        if candidate is not None:
            completed = obj.mesh is not None and obj.mesh.library == "completion"
            if fills_box(np.asarray(candidate.vertices), corners, inside_only=completed):
                mesh, source = candidate, "scene.glb"
            else:
                stale.append(obj.id)
        if mesh is None and obj.mesh is not None and obj.box_3d is not None:
            try:
                built, kind = _from_mesh_ref(obj, models_dir)
                mesh, source = built, "user model" if kind == "user model" else "library"
            except ValueError as exc:
                notes.append(f"{obj.id}: {exc}; its box is shown")
        if mesh is None:
            mesh, source = _box_mesh(corners), "box"
        meshes[obj.id] = ObjectMesh(
            vertices=np.asarray(mesh.vertices, dtype=np.float32),
            faces=np.asarray(mesh.faces, dtype=np.int32),
            source=source,
        )
    if stale:
        notes.append(
            f"the GLB's meshes do not fill the boxes of {', '.join(stale)} (a GLB of another "
            "revision?); rebuilt or boxed instead"
        )
    return MeshPlan(meshes, notes)
