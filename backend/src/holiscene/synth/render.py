"""A small ray-casting renderer (Embree through trimesh) that also returns exact instance and
depth buffers: the photo and its ground truth come from the same rays."""

from __future__ import annotations

from dataclasses import dataclass

import cv2
import numpy as np
import trimesh
from numpy.typing import NDArray

from ..geometry.camera import PinholeCamera
from .materials import Material
from .raycast import MISS, RayCaster

ROOM_INSTANCE = -1  # instance id of floor, walls and ceiling
NO_HIT = -2


@dataclass(frozen=True)
class RenderItem:
    mesh: trimesh.Trimesh  # world frame
    instance: int  # object index, or ROOM_INSTANCE
    material: Material


@dataclass(frozen=True)
class Lighting:
    position: NDArray[np.float64]  # a ceiling lamp, world frame
    intensity: float
    ambient: float


@dataclass(frozen=True)
class Frame:
    rgb: NDArray[np.uint8]  # (H, W, 3)
    instance: NDArray[np.int32]  # (H, W): object index, ROOM_INSTANCE or NO_HIT
    depth: NDArray[np.float32]  # (H, W): metres along the optical axis, 0 where nothing was hit


def _pixel_grid(width: int, height: int) -> NDArray[np.float64]:
    u, v = np.meshgrid(np.arange(width) + 0.5, np.arange(height) + 0.5)
    return np.column_stack([u.ravel(), v.ravel()])


def render(
    items: list[RenderItem],
    camera: PinholeCamera,
    size: tuple[int, int],
    lighting: Lighting,
    noise_sigma: float,
    rng: np.random.Generator,
    texture_from_world: NDArray[np.float64] | None = None,
) -> Frame:
    """Render items seen by `camera`. Textures are laid out in the frame given by the
    rotation `texture_from_world` (the room's, so floor tiles and grain follow the walls)."""
    width, height = size
    texture = np.eye(3) if texture_from_world is None else texture_from_world
    vertices, faces_all, face_item = _merged(items)
    caster = RayCaster(vertices, faces_all)
    all_rays = camera.ray(_pixel_grid(width, height))
    faces, distances = caster.first_hits(np.zeros_like(all_rays), all_rays)
    ray_index = np.flatnonzero(faces != MISS)
    tri = faces[ray_index]
    rays = all_rays[ray_index]
    hits = rays * distances[ray_index, None]

    instance = np.full(width * height, NO_HIT, dtype=np.int32)
    item_of_ray = face_item[tri]
    instance[ray_index] = np.array([items[k].instance for k in range(len(items))])[item_of_ray]
    optical_axis = camera.optical_axis
    depth = np.zeros(width * height, dtype=np.float32)
    depth[ray_index] = hits @ optical_axis

    corners = vertices[faces_all]
    face_normals = np.cross(corners[:, 1] - corners[:, 0], corners[:, 2] - corners[:, 0])
    face_normals /= np.maximum(np.linalg.norm(face_normals, axis=1, keepdims=True), 1e-12)
    normals = face_normals[tri]
    facing_away = np.einsum("ij,ij->i", normals, rays) > 0
    normals[facing_away] *= -1
    albedo = np.zeros_like(hits)
    for k in np.unique(item_of_ray):
        sel = item_of_ray == k
        albedo[sel] = items[k].material.albedo(hits[sel] @ texture.T, normals[sel] @ texture.T)

    radiance = albedo * _irradiance(caster, hits, normals, lighting)[:, None]
    image = np.zeros((width * height, 3))
    image[ray_index] = radiance
    return Frame(
        rgb=_sensor(image.reshape(height, width, 3), noise_sigma, rng),
        instance=instance.reshape(height, width),
        depth=depth.reshape(height, width),
    )


def _merged(
    items: list[RenderItem],
) -> tuple[NDArray[np.float64], NDArray[np.int64], NDArray[np.int64]]:
    """All meshes as one vertex and face array, and the item index of every face."""
    offsets = np.cumsum([0] + [len(item.mesh.vertices) for item in items[:-1]])
    vertices = np.vstack([np.asarray(item.mesh.vertices) for item in items])
    faces = np.vstack(
        [np.asarray(item.mesh.faces) + offset for item, offset in zip(items, offsets, strict=True)]
    )
    face_item = np.repeat(np.arange(len(items)), [len(item.mesh.faces) for item in items])
    return vertices, faces, face_item


def _irradiance(
    caster: RayCaster,
    points: NDArray[np.float64],
    normals: NDArray[np.float64],
    lighting: Lighting,
) -> NDArray[np.float64]:
    """Ambient + sky-ish hemisphere + a point light with hard shadows."""
    to_light = lighting.position - points
    distance = np.linalg.norm(to_light, axis=1)
    direction = to_light / np.maximum(distance, 1e-9)[:, None]
    lambert = np.clip(np.einsum("ij,ij->i", normals, direction), 0.0, None)
    lit = lambert > 0
    shadowed = np.zeros(len(points), dtype=bool)
    if lit.any():
        starts = points[lit] + normals[lit] * 2e-3
        shadowed[lit] = caster.blocked(starts, direction[lit], distance[lit] - 1e-2)
    falloff = 1.0 / (1.0 + 0.08 * distance**2)
    direct = lighting.intensity * lambert * falloff * ~shadowed
    hemisphere = 0.08 * (normals[:, 1] + 1.0) + 0.08  # light bounced off the floor reaches up too
    result: NDArray[np.float64] = lighting.ambient + hemisphere + direct
    return result


def _sensor(
    linear: NDArray[np.float64], noise_sigma: float, rng: np.random.Generator
) -> NDArray[np.uint8]:
    """Exposure, gamma, a touch of lens blur and sensor noise."""
    exposure = 0.9 / max(float(np.percentile(linear, 97)), 1e-6)
    srgb = (np.clip(linear * exposure, 0.0, 1.0) ** (1 / 2.2) * 255.0).astype(np.float32)
    blurred = cv2.GaussianBlur(srgb, (0, 0), 0.7)
    noisy = blurred + rng.normal(0.0, noise_sigma, size=blurred.shape)
    result: NDArray[np.uint8] = np.clip(noisy, 0, 255).astype(np.uint8)
    return result
