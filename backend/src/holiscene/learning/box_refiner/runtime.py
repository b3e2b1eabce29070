"""The box refiner at run time (onnxruntime, no PyTorch): a photo's placed objects in, their
boxes moved along their rays and resized by the ensemble's log ratios out, each with the
chance that it is right (`confidence`)."""

from __future__ import annotations

import json
from dataclasses import dataclass
from functools import lru_cache
from pathlib import Path

import numpy as np
from holiscene_schema import Box3D

from .confidence import ConfidenceModel, confidence_features
from .features import TARGETS, SceneView, object_features, pair_features, refined

MODEL_DIR = Path(__file__).resolve().parents[1] / "box_refiner_model"


@dataclass(frozen=True)
class RefinedBox:
    box: Box3D
    confidence: float  # the chance that `box` overlaps the true box at 3D IoU 0.15


class BoxRefiner:
    def __init__(self, model_dir: Path = MODEL_DIR) -> None:
        import onnxruntime as ort

        metadata = json.loads((model_dir / "metadata.json").read_text())
        self.classes: list[str] = metadata["classes"]
        self.mean = np.asarray(metadata["mean"], dtype=np.float32)
        self.std = np.asarray(metadata["std"], dtype=np.float32)
        self.output: str = metadata["output"]
        self.confidence = ConfidenceModel.from_json(metadata["confidence"])
        options = ort.SessionOptions()
        options.intra_op_num_threads = 1
        self.session = ort.InferenceSession(
            str(model_dir / metadata["model"]), options, providers=["CPUExecutionProvider"]
        )

    def outputs(self, view: SceneView) -> np.ndarray:
        """(placed objects, 12) in the order of `view.placed()`: per target the log ratio,
        the log expected error and the members' spread (`net.OUTPUT_PARTS`)."""
        placed = view.placed()
        if not placed:
            return np.zeros((0, 3 * len(TARGETS)), dtype=np.float32)
        objects = (object_features(view, self.classes) - self.mean) / self.std
        result: np.ndarray = self.session.run(
            [self.output],
            {"objects": objects[None].astype(np.float32), "pairs": pair_features(placed)[None]},
        )[0][0]
        return result

    def log_ratios(self, view: SceneView) -> np.ndarray:
        """(placed objects, 4): the ensemble's log ratios, in the order of `view.placed()`."""
        return self.outputs(view)[:, : len(TARGETS)]

    def refine(self, view: SceneView) -> dict[str, RefinedBox]:
        """Object id -> its refined box and how sure the refiner is of it, for every object
        with a box."""
        n = len(TARGETS)
        placed = view.placed()
        rows = self.outputs(view)
        boxes = [
            refined(view.boxes[obj.id], row[:n])  # type: ignore[arg-type]
            for obj, row in zip(placed, rows, strict=True)
        ]
        if not boxes:
            return {}
        features = np.stack(
            [
                confidence_features(box, row[n : 2 * n], row[2 * n :])
                for box, row in zip(boxes, rows, strict=True)
            ]
        )
        chances = self.confidence.chance(features)
        return {
            obj.id: RefinedBox(box, round(float(chance), 4))
            for obj, box, chance in zip(placed, boxes, chances, strict=True)
        }


@lru_cache(maxsize=2)
def box_refiner(model_dir: Path = MODEL_DIR) -> BoxRefiner:
    return BoxRefiner(model_dir)
