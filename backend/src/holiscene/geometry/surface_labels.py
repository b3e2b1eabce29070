"""Which room surface each pixel sees: floor, ceiling, a front-facing wall or a side wall.

This is the "orientation map" of layout estimation (Hedau et al. label surfaces by their
orientation): the Surface Network (`learning/surface_net.py`) predicts it from the photo, and
room hypotheses are scored by how well their own labels agree with it. Front walls are the
ones whose normal is the room axis nearer the camera's heading (the Manhattan frame's room x,
whose yaw is within 45 degrees of the heading); side walls face across.

Labels ignore furniture: a pixel on a sofa is labelled with the wall or floor behind it, so
the network learns to see the room's box through the clutter.
"""

from __future__ import annotations

import cv2
import numpy as np
from holiscene_schema import Scene
from numpy.typing import NDArray

from .camera import FloatArray, PinholeCamera

SURFACES = ("front", "back", "left", "right", "floor", "ceiling")  # the box's six faces
SURFACE_CLASSES = ("floor", "ceiling", "front_wall", "side_wall")  # what the network tells
FLOOR, CEILING, FRONT_WALL, SIDE_WALL = range(len(SURFACE_CLASSES))
CLASS_OF_SURFACE = np.array([FRONT_WALL, FRONT_WALL, SIDE_WALL, SIDE_WALL, FLOOR, CEILING])
INPUT_SIZE = (128, 96)  # (width, height) of the photo as the network reads it
MAP_SIZE = (64, 48)  # (width, height) of the label map it predicts
PIXEL_MEAN = np.array([0.485, 0.456, 0.406], dtype=np.float32)
PIXEL_STD = np.array([0.229, 0.224, 0.225], dtype=np.float32)


def map_pixels(width: int, height: int) -> FloatArray:
    """Photo pixel coordinates (N, 2) of the map cells' centres, row by row."""
    map_w, map_h = MAP_SIZE
    xs = (np.arange(map_w) + 0.5) * width / map_w
    ys = (np.arange(map_h) + 0.5) * height / map_h
    grid_x, grid_y = np.meshgrid(xs, ys)
    return np.column_stack([grid_x.ravel(), grid_y.ravel()])


def normalised_batch(images: NDArray[np.generic]) -> NDArray[np.float32]:
    """RGB images (N, H, W, 3) in 0-255 as the network reads them: (N, 3, H, W), normalised.
    Training and inference both go through here, so they can never disagree."""
    scaled = images.astype(np.float32) / 255.0
    normalised: NDArray[np.float32] = (scaled - PIXEL_MEAN) / PIXEL_STD
    return np.ascontiguousarray(normalised.transpose(0, 3, 1, 2))


def network_input(rgb: NDArray[np.uint8]) -> NDArray[np.float32]:
    """The photo as the network reads it: (1, 3, H, W), resized by area, normalised."""
    return normalised_batch(cv2.resize(rgb, INPUT_SIZE, interpolation=cv2.INTER_AREA)[None])


def hit_distances(
    rays_room: FloatArray, front: float, back: float, left: float, right: float,
    floor: float, ceiling: float,
) -> FloatArray:  # fmt: skip
    """How far along each ray (room axes: x front, y up, z right) it meets the plane of each
    face (columns in SURFACES order) of the box x in [-back, front], y in [-floor, ceiling],
    z in [-left, right]; infinite for a face the ray runs away from."""
    rx, ry, rz = rays_room[:, 0], rays_room[:, 1], rays_room[:, 2]
    with np.errstate(divide="ignore", invalid="ignore"):
        t: FloatArray = np.column_stack([
            np.where(rx > 0, front / rx, np.inf), np.where(rx < 0, -back / rx, np.inf),
            np.where(rz < 0, -left / rz, np.inf), np.where(rz > 0, right / rz, np.inf),
            np.where(ry < 0, -floor / ry, np.inf), np.where(ry > 0, ceiling / ry, np.inf),
        ])  # fmt: skip
    return t


def nearest_surface(
    rays_room: FloatArray, front: float, back: float, left: float, right: float,
    floor: float, ceiling: float,
) -> NDArray[np.int64]:  # fmt: skip
    """The surface (an index into SURFACES) each ray meets first (`hit_distances`' box)."""
    t = hit_distances(rays_room, front, back, left, right, floor, ceiling)
    result: NDArray[np.int64] = np.argmin(t, axis=1)
    return result


def true_surface_map(scene: Scene) -> NDArray[np.uint8]:
    """The label map (MAP_SIZE rows x columns) of a scene with a true camera and room box."""
    camera_info, corners = scene.camera, scene.layout.corners_3d
    if camera_info is None or corners is None or camera_info.pitch_deg is None:
        raise ValueError(f"{scene.name}: no camera pitch/roll or room corners to label from")
    camera = PinholeCamera(
        np.array(camera_info.K), camera_info.pitch_deg, camera_info.roll_deg or 0.0
    )
    box = np.array(corners, dtype=float)  # contract order: floor 0-3, ceiling 4-7
    axis_a, axis_b = box[1] - box[0], box[3] - box[0]
    # Room x is the horizontal axis nearer the camera's heading (world +x).
    if abs(axis_a[0]) / np.linalg.norm(axis_a) < abs(axis_b[0]) / np.linalg.norm(axis_b):
        axis_a, axis_b = axis_b, axis_a
    x_axis = axis_a / np.linalg.norm(axis_a) * np.sign(axis_a[0] or 1.0)
    y_axis = np.array([0.0, 1.0, 0.0])
    z_axis = np.cross(x_axis, y_axis)
    to_room = np.column_stack([x_axis, y_axis, z_axis])  # world -> room: v @ to_room
    local = box @ to_room
    low, high = local.min(axis=0), local.max(axis=0)
    rays = camera.ray(map_pixels(scene.image.width, scene.image.height)) @ to_room
    faces = nearest_surface(rays, high[0], -low[0], -low[2], high[2], -low[1], high[1])
    return CLASS_OF_SURFACE[faces].reshape(MAP_SIZE[1], MAP_SIZE[0]).astype(np.uint8)
