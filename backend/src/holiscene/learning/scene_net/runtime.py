"""The layout and object networks at run time (onnxruntime, one thread): the COCO backbone's
features (`features`), the committed model (`scene_net_model/`), and the estimates decoded
(`outputs`). One photo's features are kept, so the layout and the boxes stages of one photo
run the backbone once."""

from __future__ import annotations

import hashlib
from collections.abc import Sequence
from dataclasses import dataclass
from functools import lru_cache
from pathlib import Path

import numpy as np
from holiscene_schema import Box3D, SceneObject
from numpy.typing import NDArray

from ...geometry.camera import PinholeCamera
from ..box_refiner.features import pair_features
from ..budget import single_thread_session
from ..detector.backbone import FeatureExtractor
from ..detector.runtime import COCO_DETECTOR_DIR
from ..detector.runtime import MODEL_FILE as DETECTOR_MODEL_FILE
from .features import PhotoFeatures, photo_features
from .outputs import object_estimates, room_estimate
from .targets import ObjectTargets, RoomTargets

SCENE_NET_DIR = Path(__file__).resolve().parent.parent / "scene_net_model"
MODEL_FILE = "model.onnx"


class SceneNetModelError(RuntimeError):
    """The scene network's model is missing or unreadable."""


@dataclass(frozen=True)
class SceneNetEstimate:
    room: RoomTargets
    objects: dict[str, ObjectTargets]  # by object id

    def boxes(self, objects: Sequence[SceneObject], camera: PinholeCamera) -> dict[str, Box3D]:
        """Each object's 3D box seen by `camera` (the LEN's own, or another stage's)."""
        return {
            o.id: self.objects[o.id].box(tuple(o.bbox), o.cls, camera)
            for o in objects
            if o.id in self.objects
        }


class SceneNetwork:
    def __init__(self, model_dir: Path = SCENE_NET_DIR) -> None:
        model_file = model_dir / MODEL_FILE
        if not model_file.is_file():
            raise SceneNetModelError(f"no scene network at {model_file}")
        try:
            self.session = single_thread_session(model_file)
        except Exception as error:  # onnxruntime raises its own untyped errors
            raise SceneNetModelError(f"cannot load {model_file}: {error}") from None
        self.extractor = FeatureExtractor(COCO_DETECTOR_DIR / DETECTOR_MODEL_FILE, threads=1)
        self._last: tuple[str, PhotoFeatures] | None = None

    def _features(
        self, rgb: NDArray[np.uint8], K: NDArray[np.float64], objects: Sequence[SceneObject]
    ) -> PhotoFeatures:
        digest = hashlib.sha1(rgb.tobytes())
        digest.update(np.asarray(K, dtype=np.float64).tobytes())
        for o in objects:
            digest.update(f"{o.cls}:{o.bbox}".encode())
        key = digest.hexdigest()
        if self._last is None or self._last[0] != key:
            boxes, classes = [o.bbox for o in objects], [o.cls for o in objects]
            self._last = (key, photo_features(self.extractor, rgb, K, boxes, classes))
        return self._last[1]

    def estimate(
        self, rgb: NDArray[np.uint8], K: NDArray[np.float64], objects: Sequence[SceneObject]
    ) -> SceneNetEstimate:
        features = self._features(rgb, K, objects)
        room_rows, object_rows = self.session.run(
            None,
            {
                "room": features.room[None],
                "camera": features.camera[None],
                "objects": features.objects[None],
                "pairs": pair_features(list(objects))[None],
            },
        )
        estimates = object_estimates(object_rows[0])
        return SceneNetEstimate(
            room_estimate(room_rows[0]),
            {o.id: e for o, e in zip(objects, estimates, strict=True)},
        )


@lru_cache(maxsize=2)
def scene_network(model_dir: Path = SCENE_NET_DIR) -> SceneNetwork:
    return SceneNetwork(model_dir)
