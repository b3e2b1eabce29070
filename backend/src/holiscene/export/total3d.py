"""Stored scenes as Total3DUnderstanding's files: per scene its demo input (img.jpg,
cam_K.txt, detections.json) and the camera, room layout, 3D boxes and object meshes as its
demo writes its results (r_ex.mat, layout.mat, bdb_3d.mat, <index>_<class id>.obj), plus our
supports.json, each box's mask and the scene's gt.json when it has one, so the folder is also
an input folder that imports back to the same scene labels.

Total3D's world frame is ours (origin at the camera, x forward, y up, z right), so the
conversion is only of how rotations and boxes are written (docs/architecture.md,
"Conventions"):
- cam_R (r_ex.mat) takes (forward, up, right) camera coordinates to the world:
  Rz(pitch) Rx(roll) with Total3D's pitch positive looking up, which is our
  Rz(-pitch_deg) Rx(roll_deg);
- a box is {basis, coeffs, centroid}: basis rows are its axes, coeffs its half-sizes along
  them, and row 2 is the object's front. Ours (size along front, up, right; yaw about +y) has
  rows (-right, up, front) = ((-sin yaw, 0, -cos yaw), (0, 1, 0), (cos yaw, 0, -sin yaw)),
  coeffs (size z, size y, size x) / 2: Total3D's orientation angle is yaw + 90 degrees;
- Total3D lists a box's 8 corners top face first; for the room (layout.mat) its basis rows
  are the room's own x, y, z;
- an object's .obj is in its box's frame, coordinates along the basis rows: Total3D's viewer
  centres a mesh's bounds, stretches them to the coeffs, turns by the basis and moves it to
  the centroid.
"""

from __future__ import annotations

import io
import math
from pathlib import Path

import numpy as np
from holiscene_schema import NYU40_CLASSES, Box3D, Camera, Scene
from PIL import Image

from ..core.atomic_files import write_atomic
from ..geometry.camera import default_intrinsics, rot_x, rot_z
from ..pipeline.stages.camera import ASSUMED_HFOV_DEG
from ..viewer.meshes import object_meshes
from .archive import ArchivedScene
from .input_folder import write_labels
from .matfile import MatCell, MatStruct, mat_file

# Total3D's class list (configs/data_config.py) is NYU-40 with "void" at 0, so an index is an
# NYU-40 label; one name is spelled its own way.
TOTAL3D_CLASSES: tuple[str, ...] = (
    "void",
    *("refridgerator" if name == "refrigerator" else name for name in NYU40_CLASSES),
)
# Total3D's corners (signs along its basis rows: -+-, -++, +++, ++-, then the same below) as
# indices of ours (BOX_CORNER_SIGNS: the bottom face, then the top face).
LAYOUT_CORNERS = (4, 7, 6, 5, 0, 3, 2, 1)
JPEG_QUALITY = 95


def total3d_class(cls: str) -> str:
    return TOTAL3D_CLASSES[NYU40_CLASSES.index(cls) + 1]


def camera_rotation(camera: Camera) -> np.ndarray:
    """cam_R: world from (forward, up, right) camera coordinates."""
    assert camera.pitch_deg is not None and camera.roll_deg is not None
    return rot_z(-math.radians(camera.pitch_deg)) @ rot_x(math.radians(camera.roll_deg))


def layout_corners(corners_3d: list[list[float]]) -> np.ndarray:
    """layout.mat's 8x3 corners of the room box, in Total3D's order."""
    return np.asarray(corners_3d, dtype=float)[list(LAYOUT_CORNERS)]


def box_struct(box: Box3D | None, cls: str) -> MatStruct:
    """One entry of bdb_3d.mat's `bdb`; an object without a 3D box gets NaNs, so entry i is
    still detections.json's box i."""
    label = np.array(NYU40_CLASSES.index(cls) + 1, dtype=np.int64)
    if box is None:
        nan = np.full(3, np.nan)
        return MatStruct(
            {"basis": np.full((3, 3), np.nan), "coeffs": nan, "centroid": nan, "classid": label}
        )
    basis, coeffs, centroid = box_frame(box)
    return MatStruct({"basis": basis, "coeffs": coeffs, "centroid": centroid, "classid": label})


def box_frame(box: Box3D) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Total3D's (basis, coeffs, centroid) of a box."""
    yaw = math.radians(box.yaw_deg)
    front = [math.cos(yaw), 0.0, -math.sin(yaw)]
    left = [-math.sin(yaw), 0.0, -math.cos(yaw)]
    length, height, width = box.size
    basis = np.array([left, [0.0, 1.0, 0.0], front])
    return basis, np.array([width, height, length]) / 2.0, np.array(box.center, dtype=float)


def object_obj_files(scene: Scene, glb: bytes | None) -> dict[str, bytes]:
    """`<index>_<class id>.obj` per object with a 3D box (index as in detections.json and
    bdb_3d.mat): its mesh as the 3D view draws it (the scene's GLB, else its library model,
    else its box), in its box's frame (see the module's description)."""
    meshes = object_meshes(scene, glb).meshes
    files: dict[str, bytes] = {}
    for index, obj in enumerate(scene.objects):
        mesh = meshes.get(obj.id)
        if mesh is None or obj.box_3d is None:
            continue
        basis, _, centroid = box_frame(obj.box_3d)
        local = (mesh.vertices.astype(float) - centroid) @ basis.T
        files[f"{index}_{NYU40_CLASSES.index(obj.cls) + 1}.obj"] = obj_text(local, mesh.faces)
    return files


def obj_text(vertices: np.ndarray, faces: np.ndarray) -> bytes:
    """A Wavefront OBJ of vertices and triangles only (its face indices count from 1)."""
    lines = [f"v {x:.6f} {y:.6f} {z:.6f}" for x, y, z in vertices]
    lines += [f"f {a + 1} {b + 1} {c + 1}" for a, b, c in faces]
    return ("\n".join(lines) + "\n").encode()


def jpeg_photo(photo: Path) -> bytes:
    """img.jpg, which Total3D's demo reads: a JPEG as it is, another photo encoded as one."""
    with Image.open(photo) as image:
        if image.format == "JPEG":
            return photo.read_bytes()
        buffer = io.BytesIO()
        image.convert("RGB").save(buffer, "JPEG", quality=JPEG_QUALITY)
        return buffer.getvalue()


def write_total3d_scene(item: ArchivedScene, folder: Path) -> None:
    """One scene's folder (see the module's description)."""
    scene = item.scene
    folder.mkdir(exist_ok=True)
    write_atomic(folder / "img.jpg", jpeg_photo(item.photo))
    camera = scene.camera
    # Total3D's demo needs cam_K.txt: a scene not yet run gets the intrinsics the pipeline assumes.
    K = (
        camera.K
        if camera is not None
        else default_intrinsics(scene.image.width, scene.image.height, ASSUMED_HFOV_DEG)
    )
    write_labels(item, folder, total3d_class, K)
    if camera is not None and camera.pitch_deg is not None and camera.roll_deg is not None:
        write_atomic(folder / "r_ex.mat", mat_file({"cam_R": camera_rotation(camera)}))
    if scene.layout.corners_3d is not None:
        corners = layout_corners(scene.layout.corners_3d)
        write_atomic(folder / "layout.mat", mat_file({"layout": corners}))
    if any(obj.box_3d is not None for obj in scene.objects):
        boxes = MatCell([box_struct(obj.box_3d, obj.cls) for obj in scene.objects])
        labels = np.array([NYU40_CLASSES.index(o.cls) + 1 for o in scene.objects], dtype=np.int64)
        write_atomic(folder / "bdb_3d.mat", mat_file({"bdb": boxes, "class_id": labels}))
    glb = item.glb.read_bytes() if item.glb is not None and item.glb.is_file() else None
    for name, data in object_obj_files(scene, glb).items():
        write_atomic(folder / name, data)


def write_total3d(chosen: list[ArchivedScene], out: Path) -> None:
    """DIR/<scene name>/ per scene, named as the scene export names them."""
    from .folders import unique_stems  # here: folders imports this module for its table

    for item, stem in zip(chosen, unique_stems(chosen), strict=True):
        write_total3d_scene(item, out / stem)
