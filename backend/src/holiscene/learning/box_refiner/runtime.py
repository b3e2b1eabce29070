"""The box refiner at run time (onnxruntime, no PyTorch): a photo's placed objects in, their
boxes moved along their rays and resized by the network's log ratios out."""

from __future__ import annotations

import json
from functools import lru_cache
from pathlib import Path

import numpy as np
from holiscene_schema import Box3D

from .features import SceneView, object_features, pair_features, refined

MODEL_DIR = Path(__file__).resolve().parents[1] / "box_refiner_model"


class BoxRefiner:
    def __init__(self, model_dir: Path = MODEL_DIR) -> None:
        import onnxruntime as ort

        metadata = json.loads((model_dir / "metadata.json").read_text())
        self.classes: list[str] = metadata["classes"]
        self.mean = np.asarray(metadata["mean"], dtype=np.float32)
        self.std = np.asarray(metadata["std"], dtype=np.float32)
        options = ort.SessionOptions()
        options.intra_op_num_threads = 1
        self.session = ort.InferenceSession(
            str(model_dir / metadata["model"]), options, providers=["CPUExecutionProvider"]
        )

    def log_ratios(self, view: SceneView) -> np.ndarray:
        """(placed objects, 4): the network's log ratios, in the order of `view.placed()`."""
        placed = view.placed()
        if not placed:
            return np.zeros((0, 4), dtype=np.float32)
        objects = (object_features(view, self.classes) - self.mean) / self.std
        result: np.ndarray = self.session.run(
            ["log_ratios"],
            {"objects": objects[None].astype(np.float32), "pairs": pair_features(placed)[None]},
        )[0][0]
        return result

    def refine(self, view: SceneView) -> dict[str, Box3D]:
        """Object id -> its refined box, for every object with a box."""
        placed = view.placed()
        ratios = self.log_ratios(view)
        return {
            obj.id: refined(view.boxes[obj.id], row)  # type: ignore[arg-type]
            for obj, row in zip(placed, ratios, strict=True)
        }


@lru_cache(maxsize=2)
def box_refiner(model_dir: Path = MODEL_DIR) -> BoxRefiner:
    return BoxRefiner(model_dir)
