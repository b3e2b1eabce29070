"""First-hit ray casting with Embree (the embreex package), straight to distances and faces.

trimesh's wrapper also computes hit locations in Python, which costs more than the casting;
here a hit point is origin + distance * direction, computed only where needed.
"""

from __future__ import annotations

import numpy as np
from embreex import rtcore_scene
from embreex.mesh_construction import TriangleMesh
from numpy.typing import NDArray

MISS = -1


class RayCaster:
    def __init__(self, vertices: NDArray[np.float64], faces: NDArray[np.int64]) -> None:
        self._scene = rtcore_scene.EmbreeScene()
        TriangleMesh(
            scene=self._scene,
            vertices=np.asarray(vertices, dtype=np.float32),
            indices=np.asarray(faces, dtype=np.int32),
        )

    def first_hits(
        self, origins: NDArray[np.float64], directions: NDArray[np.float64]
    ) -> tuple[NDArray[np.int64], NDArray[np.float64]]:
        """Face index of the first hit (MISS for none) and its distance along unit directions."""
        result = self._scene.run(
            np.ascontiguousarray(origins, dtype=np.float32),
            np.ascontiguousarray(directions, dtype=np.float32),
            output=1,
        )
        return result["primID"].astype(np.int64), result["tfar"].astype(np.float64)

    def blocked(
        self,
        origins: NDArray[np.float64],
        directions: NDArray[np.float64],
        distances: NDArray[np.float64],
    ) -> NDArray[np.bool_]:
        """Whether anything lies on each segment origin -> origin + distance * direction."""
        faces = self._scene.run(
            np.ascontiguousarray(origins, dtype=np.float32),
            np.ascontiguousarray(directions, dtype=np.float32),
            dists=np.ascontiguousarray(distances, dtype=np.float32),
        )
        result: NDArray[np.bool_] = np.asarray(faces) != MISS
        return result
