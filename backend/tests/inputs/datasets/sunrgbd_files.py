"""A synthetic room written as a SUN RGB-D image folder, in SUN's own frames as its toolbox
reads them (readframeSUNRGBD.m, read3dPoints.m), so an import can be checked against the
generator's exact ground truth."""

from __future__ import annotations

import json
import math
from pathlib import Path
from typing import Any

import cv2
import numpy as np
from holiscene.geometry.camera import PinholeCamera
from holiscene.segmentation.rle import decode_mask
from holiscene_schema import Scene
from PIL import Image

# The toolbox's camera frame from OpenCV's: (x, y, z) -> (x, z, -y), x right, y forward, z up.
TOOLBOX_FROM_CV = np.array([[1.0, 0.0, 0.0], [0.0, 0.0, 1.0], [0.0, -1.0, 0.0]])
# The toolbox's upright frame (right, forward, up) from the world's (forward, up, right).
TOOLBOX_FROM_WORLD = np.array([[0.0, 0.0, 1.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]])


def rot_up(angle_deg: float) -> np.ndarray:
    """A turn about the toolbox's up axis (z)."""
    c, s = math.cos(math.radians(angle_deg)), math.sin(math.radians(angle_deg))
    return np.array([[c, -s, 0.0], [s, c, 0.0], [0.0, 0.0, 1.0]])


def upright_from_world(heading_deg: float) -> np.ndarray:
    """The toolbox's upright frame, its horizontal axes turned `heading_deg` away from the
    camera's heading (SUN's gravity frame need not follow the camera)."""
    result: np.ndarray = rot_up(heading_deg) @ TOOLBOX_FROM_WORLD
    return result


def extrinsics_rows(truth: Scene, heading_deg: float) -> np.ndarray:
    """The extrinsics file's 3x4 rows: the toolbox turns them into Rtilt = A E A^T (A =
    TOOLBOX_FROM_CV) and takes upright points as Rtilt @ (toolbox camera points); so E is
    A^T Rtilt A, with Rtilt = upright_from_world @ world_from_cv @ A^T."""
    assert truth.camera is not None and truth.camera.pitch_deg is not None
    camera = PinholeCamera(
        np.array(truth.camera.K), truth.camera.pitch_deg, truth.camera.roll_deg or 0.0
    )
    rtilt = upright_from_world(heading_deg) @ camera.world_from_cv @ TOOLBOX_FROM_CV.T
    rows = TOOLBOX_FROM_CV.T @ rtilt @ TOOLBOX_FROM_CV
    return np.hstack([rows, np.zeros((3, 1))])


def sun_polygon(
    world_points: np.ndarray, y_top: float, y_bottom: float, heading: float
) -> dict[str, Any]:
    """An annotation3D polygon: X and Z of the floor corners, and Ymin/Ymax, in the frame the
    toolbox reads as upright (X, Z, -Y)."""
    upright = world_points @ upright_from_world(heading).T
    return {
        "X": upright[:, 0].tolist(),
        "Z": upright[:, 1].tolist(),
        "Ymin": -y_top,
        "Ymax": -y_bottom,
        "rectangle": True,
    }


def box_floor_corners(center: list[float], size: list[float], yaw_deg: float) -> np.ndarray:
    """The 4 floor corners of a box in the toolbox's order: the first two span its front."""
    yaw = math.radians(yaw_deg)
    front = np.array([math.cos(yaw), 0.0, -math.sin(yaw)]) * size[0] / 2
    right = np.array([math.sin(yaw), 0.0, math.cos(yaw)]) * size[2] / 2
    c = np.array(center)
    return np.array([c + front - right, c + front + right, c - front + right, c - front - right])


def mask_polygons(truth: Scene, index: int) -> list[dict[str, Any]]:
    """The outline of an object's mask as a 2D polygon, as an annotator draws it: its largest
    part (each polygon is an object of its own to SUN's readers, so a sliver cut off by
    something in front is not outlined apart)."""
    obj = truth.objects[index]
    assert obj.mask is not None
    pixels = decode_mask(obj.mask, truth.image.width, truth.image.height).astype(np.uint8)
    contours, _ = cv2.findContours(pixels, cv2.RETR_EXTERNAL, cv2.CHAIN_APPROX_NONE)
    largest = max(contours, key=cv2.contourArea)
    return [{"x": largest[:, 0, 0].tolist(), "y": largest[:, 0, 1].tolist(), "object": index}]


def read_depth_mm(synth_dir: Path) -> np.ndarray:
    depth: np.ndarray = cv2.imread(str(synth_dir / "depth.png"), cv2.IMREAD_UNCHANGED)
    return depth


def write_sun_depth(path: Path, millimetres: np.ndarray) -> None:
    """A depth PNG as SUN RGB-D stores it: 16-bit millimetres with their bits rotated left by 3
    (the toolbox undoes it with bitor(bitshift(d, -3), bitshift(d, 16 - 3)))."""
    mm = millimetres.astype(np.uint16)
    assert cv2.imwrite(str(path), np.bitwise_or(np.left_shift(mm, 3), np.right_shift(mm, 13)))


def write_sun_folder(synth_dir: Path, folder: Path, heading_deg: float = 23.0) -> Scene:
    """The generator's scene in `synth_dir` as the SUN RGB-D image folder `folder`; returns
    the generator's truth."""
    truth = Scene.model_validate_json((synth_dir / "gt.json").read_text())
    (folder / "image").mkdir(parents=True)
    Image.open(synth_dir / "img.png").convert("RGB").save(
        folder / "image" / "0000103.jpg", quality=95
    )
    (folder / "depth").mkdir()
    write_sun_depth(folder / "depth" / "0000103.png", read_depth_mm(synth_dir))
    K = np.array(truth.camera.K if truth.camera else [])
    (folder / "intrinsics.txt").write_text("\n".join(" ".join(f"{v:.9g}" for v in r) for r in K))
    (folder / "extrinsics").mkdir()
    (folder / "extrinsics" / "20140101000000.txt").write_text("0 0 0 0\n0 0 0 0\n0 0 0 0\n")
    rows = extrinsics_rows(truth, heading_deg)
    (folder / "extrinsics" / "20150227144700.txt").write_text(
        "\n".join(" ".join(f"{v:.12f}" for v in r) for r in rows) + "\n"
    )
    names = [{"name": o.cls.replace("_", " ")} for o in truth.objects]
    polygons = [p for i in range(len(truth.objects)) for p in mask_polygons(truth, i)]
    _write_json(folder / "annotation2Dfinal" / "index.json", {
        "date": "2014", "name": "0000103", "frames": [{"polygon": polygons}], "objects": names,
    })  # fmt: skip
    boxes = []
    for obj, name in zip(truth.objects, names, strict=True):
        assert obj.box_3d is not None
        b = obj.box_3d
        corners = box_floor_corners(b.center, b.size, b.yaw_deg)
        top, bottom = b.center[1] + b.size[1] / 2, b.center[1] - b.size[1] / 2
        boxes.append({**name, "polygon": [sun_polygon(corners, top, bottom, heading_deg)]})
    _write_json(folder / "annotation3Dfinal" / "index.json", {"objects": boxes})
    room = np.array(truth.layout.corners_3d or [])
    floor = np.roll(room[:4], 2, axis=0)  # SUN's polygon may start at any corner
    layout = sun_polygon(floor, room[4:, 1].max(), room[:4, 1].min(), heading_deg)
    _write_json(
        folder / "annotation3Dlayout" / "index.json",
        {"objects": [{"name": "room", "polygon": [layout]}]},
    )
    return truth


def _write_json(path: Path, data: Any) -> None:
    path.parent.mkdir(parents=True, exist_ok=True)
    path.write_text(json.dumps(data))
