"""The Surface Network's label map of a photo, and how well a room hypothesis agrees with it.

The network (trained by `learning/surface_net.py`, shipped as `learning/default_surface_model`)
gives, for each cell of a 64x48 grid, the probability that it shows the floor, the ceiling, a
front wall or a side wall. A hypothesis labels the same cells by casting their rays into its
box; its agreement is the mean probability the network gives to those labels. Inference is
onnxruntime only (no PyTorch at run time).
"""

from __future__ import annotations

from dataclasses import dataclass
from functools import lru_cache
from pathlib import Path

import numpy as np
import onnxruntime as ort
from numpy.typing import NDArray

from .camera import FloatArray, PinholeCamera
from .surface_labels import CEILING, CLASS_OF_SURFACE, MAP_SIZE, map_pixels, network_input

DEFAULT_SURFACE_MODEL = (
    Path(__file__).parent.parent / "learning" / "default_surface_model" / "model.onnx"
)
CEILING_SEEN_SHARE = 0.02  # of the photo, for the ceiling to count as seen


class SurfaceModel:
    def __init__(self, path: Path) -> None:
        if not path.is_file():
            raise FileNotFoundError(
                f"no Surface Network at {path}: train one with `holiscene train-surfaces`"
            )
        options = ort.SessionOptions()
        options.intra_op_num_threads = 1
        self.session = ort.InferenceSession(str(path), options, providers=["CPUExecutionProvider"])

    def probabilities(self, rgb: NDArray[np.uint8]) -> NDArray[np.float32]:
        """(cells, classes) probabilities, cells row by row over MAP_SIZE: the mean of the
        photo's and its mirror image's (mirroring keeps every label, as in training)."""
        plain, mirrored = (
            self.session.run(None, {"image": network_input(image)})[0][0]  # (C, h, w)
            for image in (rgb, rgb[:, ::-1])
        )
        logits = (plain + mirrored[:, :, ::-1]) / 2.0
        flat = logits.reshape(logits.shape[0], -1).T
        flat = np.exp(flat - flat.max(axis=1, keepdims=True))
        result: NDArray[np.float32] = flat / flat.sum(axis=1, keepdims=True)
        return result

    def label_map(self, rgb: NDArray[np.uint8]) -> NDArray[np.int64]:
        """The most probable class per cell, as an image of MAP_SIZE (for pictures)."""
        result: NDArray[np.int64] = self.probabilities(rgb).argmax(axis=1)
        return result.reshape(MAP_SIZE[1], MAP_SIZE[0])


@lru_cache(maxsize=2)
def load_surface_model(path: Path = DEFAULT_SURFACE_MODEL) -> SurfaceModel:
    return SurfaceModel(path)


@dataclass(frozen=True)
class SurfaceMap:
    """A photo's predicted surface probabilities with the cells' rays in room axes."""

    probabilities: NDArray[np.float32]  # (cells, classes)
    rays_room: FloatArray  # (cells, 3)

    @classmethod
    def predict(
        cls,
        model: SurfaceModel,
        rgb: NDArray[np.uint8],
        camera: PinholeCamera,
        to_room: FloatArray,
    ) -> SurfaceMap:
        height, width = rgb.shape[:2]
        rays = camera.ray(map_pixels(width, height)) @ to_room
        return cls(model.probabilities(rgb), rays)

    @property
    def ceiling_seen(self) -> bool:
        return float(self.probabilities[:, CEILING].mean()) > CEILING_SEEN_SHARE

    def agreement(self, labels_of: NDArray[np.int64]) -> float:
        """Mean probability of the classes of the faces `labels_of` (one per cell)."""
        classes = CLASS_OF_SURFACE[labels_of]
        return float(self.probabilities[np.arange(len(classes)), classes].mean())
