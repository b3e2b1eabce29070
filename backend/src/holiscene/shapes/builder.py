"""`ShapeBuilder`: collects closed parts and support surfaces, then fits them to the box.

Builders work in a *floor frame*: x in [-d/2, d/2] (front +x), y in [0, h] from the floor
up, z in [-w/2, w/2]; thinking in heights above the floor keeps the furniture code short.
`build()` moves everything into the canonical centred frame and fits it exactly to the box.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from typing import TypeVar

import numpy as np
import trimesh

from . import primitives
from .fitting import BoxFit, fit_to_box
from .shape import Interval, Shape, SupportSurface

T = TypeVar("T")


def pick(rng: np.random.Generator, options: Sequence[T], p: Sequence[float] | None = None) -> T:
    """One of `options` (typed, unlike rng.choice on a list of strings)."""
    index = int(rng.choice(len(options), p=None if p is None else np.asarray(p) / np.sum(p)))
    return options[index]


def vary(rng: np.random.Generator, lo: float, hi: float, *caps: float) -> float:
    """Uniform in [lo, hi], the whole range scaled down when hi exceeds the smallest cap.

    Parts are sized in metres (a 4 cm leg) but must shrink for a small box; scaling the
    range rather than clipping the value keeps small instances varied.
    """
    value = float(rng.uniform(lo, hi))
    cap = min(caps, default=math.inf)
    return value * min(1.0, cap / hi) if hi > 0 else value


class ShapeBuilder:
    def __init__(self, size: tuple[float, float, float]) -> None:
        self.d, self.h, self.w = size
        self.x0, self.x1 = -self.d / 2.0, self.d / 2.0
        self.z0, self.z1 = -self.w / 2.0, self.w / 2.0
        self._parts: list[tuple[str, trimesh.Trimesh]] = []
        self._surfaces: list[SupportSurface] = []

    def add(self, name: str, mesh: trimesh.Trimesh) -> None:
        self._parts.append((name, mesh))

    def box(self, name: str, x: Interval, y: Interval, z: Interval) -> None:
        self.add(name, primitives.box(x, y, z))

    def support(
        self, name: str, y: float, x: Interval, z: Interval, clearance: float = math.inf
    ) -> None:
        self._surfaces.append(SupportSurface(name, y, x, z, clearance))

    def build(self) -> Shape:
        if not self._parts:
            raise ValueError("a shape needs at least one part")
        # Stack by hand rather than trimesh.util.concatenate: no vertex merging between parts
        # (each part stays closed on its own) and face order is part order.
        vertices, faces, face_part = [], [], []
        offset = 0
        for index, (_, mesh) in enumerate(self._parts):
            vertices.append(np.asarray(mesh.vertices, dtype=float))
            faces.append(np.asarray(mesh.faces, dtype=np.int64) + offset)
            face_part.append(np.full(len(mesh.faces), index, dtype=np.int32))
            offset += len(mesh.vertices)
        raw = trimesh.Trimesh(vertices=np.vstack(vertices), faces=np.vstack(faces), process=False)
        size = (self.d, self.h, self.w)
        fit = BoxFit.between(raw.bounds, size)
        return Shape(
            mesh=fit_to_box(raw, size),
            parts=[name for name, _ in self._parts],
            face_part=np.concatenate(face_part),
            support_surfaces=[s.scaled(fit.scale, fit.offset) for s in self._surfaces],
        )
