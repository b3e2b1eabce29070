"""The 3D scene as GLB: one box mesh per placed object (node named by object id), a floor."""

from __future__ import annotations

import colorsys
import hashlib

import numpy as np
import trimesh
from holiscene_schema import Box3D

from ..geometry.boxes import box_corners
from ..geometry.camera import rot_y

FLOOR_COLOUR = (200, 200, 200, 255)


def class_colour(cls: str) -> tuple[int, int, int, int]:
    """A stable, distinct-enough RGBA colour per class name (same hue in every scene)."""
    hue = int(hashlib.sha1(cls.encode()).hexdigest()[:6], 16) / 0xFFFFFF
    r, g, b = colorsys.hsv_to_rgb(hue, 0.55, 0.9)
    return round(r * 255), round(g * 255), round(b * 255), 255


def _box_mesh(box: Box3D, colour: tuple[int, int, int, int]) -> trimesh.Trimesh:
    transform = np.eye(4)
    transform[:3, :3] = rot_y(np.radians(box.yaw_deg))
    transform[:3, 3] = box.center
    mesh = trimesh.creation.box(extents=box.size, transform=transform)
    return _painted(mesh, colour)


def _painted(mesh: trimesh.Trimesh, colour: tuple[int, int, int, int]) -> trimesh.Trimesh:
    """One material per mesh (a glTF base colour), so viewers can recolour by object."""
    material = trimesh.visual.material.PBRMaterial(
        baseColorFactor=colour, metallicFactor=0.0, roughnessFactor=0.9, doubleSided=True
    )
    mesh.visual = trimesh.visual.TextureVisuals(material=material)
    return mesh


def _floor_mesh(boxes: list[Box3D], floor_y: float) -> trimesh.Trimesh:
    """A floor quad under the objects (or 6 m ahead of the camera when there are none)."""
    if boxes:
        pts = np.vstack(
            [box_corners(np.array(b.center), np.array(b.size), b.yaw_deg) for b in boxes]
        )
        lo, hi = pts.min(axis=0) - 0.5, pts.max(axis=0) + 0.5
    else:
        lo, hi = np.array([0.5, 0.0, -3.0]), np.array([6.5, 0.0, 3.0])
    vertices = np.array(
        [
            [lo[0], floor_y, lo[2]],
            [hi[0], floor_y, lo[2]],
            [hi[0], floor_y, hi[2]],
            [lo[0], floor_y, hi[2]],
        ]
    )
    faces = np.array([[0, 2, 1], [0, 3, 2]])  # facing up (+y)
    return _painted(trimesh.Trimesh(vertices=vertices, faces=faces, process=False), FLOOR_COLOUR)


def scene_glb(placed: dict[str, tuple[str, Box3D]], floor_y: float | None) -> bytes | None:
    """GLB bytes of objects id -> (class, box) and, when known, the floor plane; None when
    there is nothing to show (no placed object and no floor)."""
    if not placed and floor_y is None:
        return None
    scene = trimesh.Scene()
    for obj_id, (cls, box) in placed.items():
        scene.add_geometry(_box_mesh(box, class_colour(cls)), node_name=obj_id, geom_name=obj_id)
    if floor_y is not None:
        boxes = [box for _, box in placed.values()]
        scene.add_geometry(_floor_mesh(boxes, floor_y), node_name="floor", geom_name="floor")
    data = scene.export(file_type="glb")
    assert isinstance(data, bytes)
    return data
