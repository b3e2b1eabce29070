"""Surface colours for the renderer: plain paint, wood grain, floor tiles, fabric, each with
random colour and scale, evaluated per pixel from the 3D hit point (so textures stay on
their surfaces as the camera moves)."""

from __future__ import annotations

from dataclasses import dataclass
from typing import Literal

import numpy as np
from numpy.typing import NDArray

Pattern = Literal["paint", "wood", "tiles", "fabric", "metal"]

# Palettes (RGB 0-1) per kind of surface; each instance jitters its pick.
_WOODS = [(0.55, 0.36, 0.2), (0.7, 0.52, 0.33), (0.35, 0.22, 0.13), (0.82, 0.68, 0.5)]
_PAINTS = [(0.93, 0.92, 0.88), (0.85, 0.82, 0.74), (0.75, 0.8, 0.83), (0.9, 0.85, 0.78),
           (0.7, 0.74, 0.66), (0.95, 0.95, 0.95), (0.82, 0.72, 0.7)]  # fmt: skip
_FABRICS = [(0.3, 0.35, 0.5), (0.6, 0.25, 0.22), (0.45, 0.5, 0.35), (0.8, 0.78, 0.72),
            (0.25, 0.25, 0.27), (0.62, 0.55, 0.45), (0.85, 0.85, 0.9)]  # fmt: skip
_METALS = [(0.6, 0.6, 0.62), (0.15, 0.15, 0.16), (0.85, 0.85, 0.86)]
_TILES = [(0.8, 0.78, 0.72), (0.55, 0.5, 0.45), (0.9, 0.9, 0.92), (0.4, 0.42, 0.45)]

PALETTES: dict[Pattern, list[tuple[float, float, float]]] = {
    "paint": _PAINTS,
    "wood": _WOODS,
    "tiles": _TILES,
    "fabric": _FABRICS,
    "metal": _METALS,
}


@dataclass(frozen=True)
class Material:
    pattern: Pattern
    colour: tuple[float, float, float]
    scale: float  # metres per pattern period
    phase: float

    def albedo(
        self, points: NDArray[np.float64], normals: NDArray[np.float64]
    ) -> NDArray[np.float64]:
        """RGB albedo (N, 3) at world points on surfaces with the given normals."""
        base: NDArray[np.float64] = np.broadcast_to(np.array(self.colour), (len(points), 3))
        shade: NDArray[np.float64] = np.ones(len(points))
        a, b = _plane_coordinates(points, normals)
        if self.pattern == "wood":
            # Wavy stripes along one in-plane axis look like grain.
            wave = np.sin((a / self.scale) * 2 * np.pi + 3 * np.sin(a * 7 + self.phase))
            shade = 0.82 + 0.2 * (0.5 + 0.5 * wave)
        elif self.pattern == "tiles":
            fa, fb = np.mod(a / self.scale, 1.0), np.mod(b / self.scale, 1.0)
            grout = (np.minimum(fa, 1 - fa) < 0.03) | (np.minimum(fb, 1 - fb) < 0.03)
            checker = (np.floor(a / self.scale) + np.floor(b / self.scale)) % 2
            shade = np.where(grout, 0.65, 0.95 + 0.06 * checker)
        elif self.pattern == "fabric":
            shade = 0.93 + 0.05 * np.sin(a * 400 + self.phase) * np.sin(b * 400)
        elif self.pattern == "paint":
            shade = 0.97 + 0.03 * np.sin(a * 3.1 + self.phase) * np.sin(b * 2.3 + self.phase * 0.7)
        result: NDArray[np.float64] = base * shade[:, None]
        return result


def _plane_coordinates(
    points: NDArray[np.float64], normals: NDArray[np.float64]
) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """Two coordinates in the surface's plane, from its dominant normal axis."""
    axis = np.argmax(np.abs(normals), axis=1)
    a = np.where(axis == 0, points[:, 2], points[:, 0])
    b = np.where(axis == 1, points[:, 2], points[:, 1])
    return a, b


def random_material(
    rng: np.random.Generator, pattern: Pattern, scale: tuple[float, float]
) -> Material:
    r, g, b = PALETTES[pattern][int(rng.integers(len(PALETTES[pattern])))]
    jitter = rng.uniform(0.9, 1.1, size=3)
    colour = tuple(float(np.clip(c * j, 0.02, 1.0)) for c, j in zip((r, g, b), jitter, strict=True))
    return Material(
        pattern=pattern,
        colour=(colour[0], colour[1], colour[2]),
        scale=float(rng.uniform(*scale)),
        phase=float(rng.uniform(0, 2 * np.pi)),
    )


# Which patterns suit which classes (first listed is the most common).
CLASS_PATTERNS: dict[str, list[Pattern]] = {
    "bed": ["fabric"], "sofa": ["fabric"], "pillow": ["fabric"], "curtain": ["fabric"],
    "chair": ["wood", "fabric", "metal"], "table": ["wood", "metal"], "desk": ["wood"],
    "dresser": ["wood", "paint"], "night_stand": ["wood", "paint"], "cabinet": ["wood", "paint"],
    "bookshelf": ["wood"], "shelves": ["wood", "metal"], "counter": ["paint", "wood"],
    "lamp": ["metal", "fabric"], "television": ["metal"], "refrigerator": ["paint", "metal"],
    "toilet": ["paint"], "sink": ["paint"], "bathtub": ["paint"], "door": ["wood", "paint"],
    "window": ["metal", "paint"], "picture": ["paint", "fabric"], "mirror": ["metal"],
    "box": ["paint", "wood"], "books": ["fabric", "paint"],
}  # fmt: skip


def object_material(rng: np.random.Generator, cls: str) -> Material:
    patterns = CLASS_PATTERNS.get(cls, ["paint"])
    return random_material(rng, patterns[int(rng.integers(len(patterns)))], (0.05, 0.25))
