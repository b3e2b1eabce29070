"""What the library returns: a `Shape` (one mesh, its parts) and its `SupportSurface`s."""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
import trimesh
from numpy.typing import NDArray

Interval = tuple[float, float]


@dataclass(frozen=True)
class SupportSurface:
    """A horizontal rectangle, in the shape's canonical frame, that things can stand on.

    `clearance` is the free height above it (up to the next shelf board, say); `math.inf`
    for an open top.
    """

    name: str
    y: float
    x_range: Interval
    z_range: Interval
    clearance: float = math.inf

    def scaled(self, scale: NDArray[np.float64], offset: NDArray[np.float64]) -> SupportSurface:
        """The same surface after the affine map p -> p * scale + offset (positive scales)."""
        sx, sy, sz = (float(s) for s in scale)
        ox, oy, oz = (float(o) for o in offset)
        return SupportSurface(
            name=self.name,
            y=self.y * sy + oy,
            x_range=(self.x_range[0] * sx + ox, self.x_range[1] * sx + ox),
            z_range=(self.z_range[0] * sz + oz, self.z_range[1] * sz + oz),
            clearance=self.clearance * sy,
        )


@dataclass
class Shape:
    """A generated object: one triangle mesh made of closed parts.

    `parts` names each part in build order (names repeat: four "leg"s); `face_part[i]` is the
    index into `parts` of the part that face `i` belongs to.
    """

    mesh: trimesh.Trimesh
    parts: list[str]
    face_part: NDArray[np.int32]
    support_surfaces: list[SupportSurface]

    def part_faces(self, name: str) -> NDArray[np.bool_]:
        """Mask of the faces of every part called `name`."""
        ids = [i for i, part in enumerate(self.parts) if part == name]
        mask: NDArray[np.bool_] = np.isin(self.face_part, ids)
        return mask
