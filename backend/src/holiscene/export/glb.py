"""The 3D scene as GLB: one mesh per placed object (node named by object id), and the room.

Objects are their fitted models when there are some, their boxes otherwise, coloured by class.
The room is the layout's cuboid when known (nodes `floor`, `ceiling`, `wall_0`..`wall_3`,
single-sided and facing inwards, so a viewer outside the room sees through the near walls),
else a floor quad under the objects.
"""

from __future__ import annotations

import colorsys
import hashlib

import numpy as np
import trimesh
from holiscene_schema import Box3D

from ..geometry.boxes import corners_of
from ..geometry.camera import rot_y

FLOOR_COLOUR = (200, 200, 200, 255)
CEILING_COLOUR = (235, 235, 235, 255)
WALL_COLOUR = (222, 218, 210, 255)


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


def _painted(
    mesh: trimesh.Trimesh, colour: tuple[int, int, int, int], double_sided: bool = True
) -> trimesh.Trimesh:
    """One material per mesh (a glTF base colour), so viewers can recolour by object."""
    material = trimesh.visual.material.PBRMaterial(
        baseColorFactor=colour, metallicFactor=0.0, roughnessFactor=0.9, doubleSided=double_sided
    )
    mesh.visual = trimesh.visual.TextureVisuals(material=material)
    return mesh


def _floor_mesh(boxes: list[Box3D], floor_y: float) -> trimesh.Trimesh:
    """A floor quad under the objects (or 6 m ahead of the camera when there are none)."""
    if boxes:
        pts = np.vstack([corners_of(b) for b in boxes])
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


def _quad(points: np.ndarray) -> trimesh.Trimesh:
    """Two triangles; counter-clockwise seen from the side the quad faces."""
    return trimesh.Trimesh(
        vertices=np.asarray(points, dtype=float),
        faces=np.array([[0, 1, 2], [0, 2, 3]]),
        process=False,
    )


def room_meshes(
    corners: np.ndarray,
) -> dict[str, tuple[trimesh.Trimesh, tuple[int, int, int, int]]]:
    """Floor, ceiling and four walls of a room cuboid (8 corners, contract order), facing in."""
    c = np.asarray(corners, dtype=float)
    centre = c.mean(axis=0)
    quads = {
        "floor": [0, 1, 2, 3],
        "ceiling": [4, 5, 6, 7],
        "wall_0": [0, 1, 5, 4],
        "wall_1": [1, 2, 6, 5],
        "wall_2": [2, 3, 7, 6],
        "wall_3": [3, 0, 4, 7],
    }
    out = {}
    for name, index in quads.items():
        points = c[index]
        normal = np.cross(points[1] - points[0], points[2] - points[0])
        if float(normal @ (centre - points.mean(axis=0))) < 0:  # turn it to face the inside
            points = points[::-1]
        colour = {"floor": FLOOR_COLOUR, "ceiling": CEILING_COLOUR}.get(name, WALL_COLOUR)
        out[name] = (_quad(points), colour)
    return out


def scene_glb(
    placed: dict[str, tuple[str, Box3D]],
    floor_y: float | None,
    meshes: dict[str, trimesh.Trimesh] | None = None,
    room_corners: np.ndarray | None = None,
) -> bytes | None:
    """GLB bytes of objects id -> (class, box), drawn as `meshes[id]` (world frame) where
    given, and of the room cuboid (or else, when known, a floor plane); None when there is
    nothing to show (no placed object, no room and no floor)."""
    if not placed and floor_y is None and room_corners is None:
        return None
    meshes = meshes or {}
    scene = trimesh.Scene()
    for obj_id, (cls, box) in placed.items():
        mesh = meshes.get(obj_id)
        geometry = _painted(mesh.copy(), class_colour(cls)) if mesh is not None else None
        if geometry is None:
            geometry = _box_mesh(box, class_colour(cls))
        scene.add_geometry(geometry, node_name=obj_id, geom_name=obj_id)
    if room_corners is not None:
        for name, (quad, colour) in room_meshes(room_corners).items():
            scene.add_geometry(
                _painted(quad, colour, double_sided=False), node_name=name, geom_name=name
            )
    elif floor_y is not None:
        boxes = [box for _, box in placed.values()]
        scene.add_geometry(_floor_mesh(boxes, floor_y), node_name="floor", geom_name="floor")
    data = scene.export(file_type="glb")
    assert isinstance(data, bytes)
    return data
