"""Fitting a mesh into a box: the last step of every generated shape and of every user model.

A shape fills its box exactly when its axis-aligned bounds equal [-size/2, size/2]; the fit
is a per-axis scale and a translation (no rotation), so a builder whose parts already reach
every face of the box is left unchanged up to rounding.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np
import trimesh
from numpy.typing import NDArray

# An axis thinner than this (a flat picture quad, say) is centred rather than stretched.
_FLAT = 1e-9


@dataclass(frozen=True)
class BoxFit:
    """The affine map p -> p * scale + offset that takes given bounds onto a centred box."""

    scale: NDArray[np.float64]
    offset: NDArray[np.float64]

    @classmethod
    def between(cls, bounds: NDArray[np.float64], size: Sequence[float]) -> BoxFit:
        lo, hi = np.asarray(bounds, dtype=float)
        target = np.asarray(size, dtype=float)
        if target.shape != (3,) or np.any(target <= 0):
            raise ValueError(f"a box size is three positive lengths, got {tuple(size)}")
        extent = hi - lo
        flat = extent < _FLAT
        scale = np.where(flat, 1.0, target / np.where(flat, 1.0, extent))
        # Map lo onto -size/2 (or the centre onto 0 along a flat axis).
        offset = np.where(flat, -(lo + hi) / 2.0, -target / 2.0 - lo * scale)
        return cls(scale=scale, offset=offset)

    def matrix(self) -> NDArray[np.float64]:
        transform = np.diag([*self.scale, 1.0])
        transform[:3, 3] = self.offset
        return transform

    def apply(self, points: NDArray[np.float64]) -> NDArray[np.float64]:
        result: NDArray[np.float64] = points * self.scale + self.offset
        return result


def fit_to_box(mesh: trimesh.Trimesh, size: Sequence[float]) -> trimesh.Trimesh:
    """A copy of `mesh` scaled per axis and moved so its bounds are [-size/2, size/2].

    size = (depth along x, height along y, width along z) in metres. An axis along which the
    mesh is flat stays flat, centred on 0.
    """
    fit = BoxFit.between(mesh.bounds, size)
    fitted = mesh.copy()
    fitted.apply_transform(fit.matrix())
    return fitted
