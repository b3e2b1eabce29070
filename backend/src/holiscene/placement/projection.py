"""IoU between projected geometry and an object's mask, at reduced resolution.

A `MaskTarget` keeps a window around the mask (downscaled so its longer side has at most
`max_side` pixels). A convex polygon (the projected hull of a box) is rasterised into the
window with `cv2.fillConvexPoly`; its area outside the window but inside the image is counted
analytically, so the IoU is over the whole image without rasterising all of it.
"""

from __future__ import annotations

import cv2
import numpy as np
from holiscene_schema import BOX_CORNER_SIGNS

from ..geometry.camera import FloatArray

_SIGNS = np.array(BOX_CORNER_SIGNS, dtype=float)
_SHIFT = 4  # fixed-point bits for sub-pixel polygon vertices
_NEAR = 0.05  # metres: points closer to the camera plane are clipped away

# The 12 edges of a box, by corner index in BOX_CORNER_SIGNS order.
BOX_EDGES = np.array(
    [[0, 1], [1, 2], [2, 3], [3, 0], [4, 5], [5, 6], [6, 7], [7, 4], [0, 4], [1, 5], [2, 6], [3, 7]]
)


def project_points(projection: FloatArray, points: FloatArray) -> FloatArray:
    """Pixels of world points in front of the camera (others dropped)."""
    homogeneous = points @ projection.T
    if homogeneous[:, 2].min() > 1e-9:
        result: FloatArray = homogeneous[:, :2] / homogeneous[:, 2:3]
        return result
    front = homogeneous[:, 2] > 1e-9
    result = homogeneous[front, :2] / homogeneous[front, 2:3]
    return result


def box_hull(projection: FloatArray, corners: FloatArray, depth_axis: FloatArray) -> FloatArray:
    """The image polygon (convex hull) of a box given by its 8 world corners; edges that
    cross the camera's near plane are clipped there. `depth_axis` is the optical axis in the
    world frame. Empty (0, 2) when the box is behind the camera."""
    depth = corners @ depth_axis
    if depth.min() > _NEAR:
        pts = project_points(projection, corners)
    else:
        keep = [corners[depth > _NEAR]]
        a, b = BOX_EDGES[:, 0], BOX_EDGES[:, 1]
        da, db = depth[a], depth[b]
        crossing = (da > _NEAR) != (db > _NEAR)
        if np.any(crossing):
            t = (_NEAR - da[crossing]) / (db[crossing] - da[crossing])
            ca, cb = corners[a[crossing]], corners[b[crossing]]
            keep.append(ca + (cb - ca) * t[:, None])
        front = np.vstack(keep)
        if len(front) < 3:
            return np.zeros((0, 2))
        pts = project_points(projection, front)
    if len(pts) < 3:
        return np.zeros((0, 2))
    hull: FloatArray = cv2.convexHull(pts.astype(np.float32)).reshape(-1, 2).astype(float)
    return hull


def box_corners_fast(
    center: FloatArray, size: FloatArray, cos_sin: tuple[float, float]
) -> FloatArray:
    """`geometry.boxes.box_corners` with the yaw's cosine and sine given (hot loop)."""
    c, s = cos_sin
    rotation_t = np.array([[c, 0.0, -s], [0.0, 1.0, 0.0], [s, 0.0, c]])
    result: FloatArray = (_SIGNS * (size * 0.5)) @ rotation_t + center
    return result


def convex_hull_mask(mask: np.ndarray) -> np.ndarray:
    """The filled convex hull of a mask's pixels (same shape, bool)."""
    ys, xs = np.nonzero(mask)
    if len(xs) < 3:
        return mask
    hull = cv2.convexHull(np.column_stack([xs, ys]).astype(np.int32))
    out = np.zeros(mask.shape, dtype=np.uint8)
    cv2.fillConvexPoly(out, hull, 1)
    result: np.ndarray = out.astype(bool) | mask
    return result


class MaskTarget:
    """One object's mask, ready for many IoU evaluations."""

    def __init__(
        self, mask: np.ndarray, max_side: int = 96, margin: float = 0.6, min_pad: int = 12
    ) -> None:
        height, width = mask.shape
        self.image_size = (width, height)
        rows, cols = np.flatnonzero(mask.any(axis=1)), np.flatnonzero(mask.any(axis=0))
        if len(rows) == 0:
            raise ValueError("empty mask")
        y0, y1, x0, x1 = int(rows[0]), int(rows[-1]) + 1, int(cols[0]), int(cols[-1]) + 1
        pad_x = max(min_pad, round((x1 - x0) * margin))
        pad_y = max(min_pad, round((y1 - y0) * margin))
        self.x0, self.y0 = max(0, x0 - pad_x), max(0, y0 - pad_y)
        self.x1, self.y1 = min(width, x1 + pad_x), min(height, y1 + pad_y)
        w, h = self.x1 - self.x0, self.y1 - self.y0
        self.scale = min(1.0, max_side / max(w, h))
        self.size = (max(1, round(w * self.scale)), max(1, round(h * self.scale)))
        window = mask[self.y0 : self.y1, self.x0 : self.x1].astype(np.float32)
        small = cv2.resize(window, self.size, interpolation=cv2.INTER_AREA) >= 0.5
        self.mask = small
        self.pixel_area = 1.0 / (self.scale * self.scale)  # full-resolution pixels per cell
        self.mask_area = float(small.sum()) * self.pixel_area
        self._canvas = np.zeros((self.size[1], self.size[0]), dtype=np.uint8)
        self._image_rect = np.array(
            [[0, 0], [width, 0], [width, height], [0, height]], dtype=np.float32
        )
        self._window_rect = np.array(
            [[self.x0, self.y0], [self.x1, self.y0], [self.x1, self.y1], [self.x0, self.y1]],
            dtype=np.float32,
        )

    def _to_window(self, pts: FloatArray) -> np.ndarray:
        local = (pts - np.array([self.x0, self.y0])) * self.scale
        fixed: np.ndarray = np.round(local * (1 << _SHIFT)).astype(np.int32)
        return fixed

    def iou_polygon(self, polygon: FloatArray) -> float:
        """IoU of a convex image polygon with the mask, over the image."""
        if len(polygon) < 3 or not np.all(np.isfinite(polygon)):
            return 0.0
        poly = polygon.astype(np.float32)
        lo, hi = poly.min(axis=0), poly.max(axis=0)
        if lo[0] >= self.x0 and lo[1] >= self.y0 and hi[0] <= self.x1 and hi[1] <= self.y1:
            in_window = in_image = abs(float(cv2.contourArea(poly)))
        else:
            width, height = self.image_size
            if lo[0] >= 0 and lo[1] >= 0 and hi[0] <= width and hi[1] <= height:
                in_image = abs(float(cv2.contourArea(poly)))
            else:
                in_image, _ = cv2.intersectConvexConvex(poly, self._image_rect)
            if in_image <= 0:
                return 0.0
            in_window, _ = cv2.intersectConvexConvex(poly, self._window_rect)
        canvas = self._canvas
        canvas[:] = 0
        if in_window > 0:
            cv2.fillConvexPoly(canvas, self._to_window(polygon), 1, cv2.LINE_8, _SHIFT)
        inside = canvas.view(bool)
        inter = float(np.count_nonzero(inside & self.mask)) * self.pixel_area
        drawn = float(np.count_nonzero(inside)) * self.pixel_area
        area = drawn + max(0.0, float(in_image) - float(in_window))
        union = area + self.mask_area - inter
        return inter / union if union > 0 else 0.0

    def silhouette(
        self, projection: FloatArray, vertices: FloatArray, faces: np.ndarray
    ) -> np.ndarray:
        """A closed mesh's silhouette in the window (bool): the union of its triangles that
        face the camera (at the origin); triangles behind the camera are left out.

        Triangles are filled one by one: `cv2.fillPoly` with several contours fills by the
        even-odd rule, so overlapping parts would cancel out."""
        canvas = np.zeros((self.size[1], self.size[0]), dtype=np.uint8)
        tri = vertices[faces]  # (F, 3, 3)
        normals = np.cross(tri[:, 1] - tri[:, 0], tri[:, 2] - tri[:, 0])
        facing = np.einsum("ij,ij->i", normals, tri[:, 0]) < 0
        homogeneous = tri[facing] @ projection.T  # (F', 3, 3)
        in_front = np.all(homogeneous[:, :, 2] > 1e-6, axis=1)
        homogeneous = homogeneous[in_front]
        pixels = homogeneous[:, :, :2] / homogeneous[:, :, 2:3]
        fixed = self._to_window(pixels.reshape(-1, 2)).reshape(-1, 3, 2)
        lo = fixed.min(axis=1)
        hi = fixed.max(axis=1)
        limit = np.array([self.size[0], self.size[1]]) << _SHIFT
        visible = np.all(hi >= 0, axis=1) & np.all(lo < limit, axis=1)
        for triangle in fixed[visible]:
            cv2.fillConvexPoly(canvas, triangle, 1, cv2.LINE_8, _SHIFT)
        return canvas.view(bool)

    def iou_silhouette(self, silhouette: np.ndarray, area_outside: float = 0.0) -> float:
        inter = float(np.count_nonzero(silhouette & self.mask)) * self.pixel_area
        area = float(np.count_nonzero(silhouette)) * self.pixel_area + area_outside
        union = area + self.mask_area - inter
        return inter / union if union > 0 else 0.0
