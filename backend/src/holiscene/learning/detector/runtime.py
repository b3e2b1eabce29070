"""The object detector at inference time: onnxruntime only, no PyTorch.

A detector directory (the committed default, or one from the registry) holds `model.onnx` and
`metadata.json` (its class list, where it came from, how it was checked). Preprocessing and
decoding follow holiscene_schema.detector_model; the browser does the same
(frontend/src/inference/detector.ts), and the shared vectors in
shared_schema/vectors/detector_model.json hold the two to the same numbers.
"""

from __future__ import annotations

import json
from dataclasses import dataclass
from functools import lru_cache
from pathlib import Path
from typing import Any

import numpy as np
import onnxruntime as ort
from holiscene_schema import NYU40_CLASSES
from holiscene_schema.detector_model import (
    COCO_TO_NYU40,
    INPUT_NAME,
    INPUT_SIZE,
    MAX_DETECTIONS,
    MIN_BOX_PX,
    NMS_IOU,
    OUTPUT_NAME,
    SCORE_THRESHOLD,
)

_LEARNING_DIR = Path(__file__).resolve().parent.parent
# The COCO CenterNet converted from its npm package (scripts/convert_coco_detector.py), the
# NYU-40 head fine-tuned on synthetic rooms over its backbone (holiscene train-detector), and
# the COCO PicoDet converted from its PyPI package (scripts/convert_picodet_detector.py).
COCO_DETECTOR_DIR = _LEARNING_DIR / "coco_detector"
NYU_DETECTOR_DIR = _LEARNING_DIR / "nyu_detector"
PICODET_DETECTOR_DIR = _LEARNING_DIR / "picodet_detector"
# The scene page's fainter suggestions: PicoDet's boxes named by a head trained on synthetic
# rooms (docs/detector.md): it knows the classes COCO lacks, and names too much for the pipeline.
SUGGESTER_DETECTOR_DIR = _LEARNING_DIR / "picodet_nyu_detector"
# The detector the pipeline uses unless told otherwise, and the one a new registry starts
# from: PicoDet finds about twice as many real objects as the CenterNet, about as precisely;
# the NYU-40 head finds more but a quarter as precisely (docs/detector.md).
DEFAULT_DETECTOR_DIR = PICODET_DETECTOR_DIR
MODEL_FILE = "model.onnx"
METADATA_FILE = "metadata.json"
LABEL_SPACES = ("coco80", "nyu40")


class DetectorModelError(ValueError):
    """A detector directory whose files are missing, corrupt or of the wrong shape."""


@dataclass(frozen=True)
class DetectedBox:
    bbox: tuple[float, float, float, float]  # x1, y1, x2, y2 in photo pixels
    score: float
    cls: str  # NYU-40
    source_class: str  # the model's own class name


def bilinear_resize(rgb: np.ndarray, size: int = INPUT_SIZE) -> np.ndarray:
    """An (H, W, 3) photo stretched to (size, size, 3) float32, half-pixel centres, clamped,
    in float64 and rounded once (the contract's preprocessing)."""
    height, width = rgb.shape[:2]
    ys = np.clip((np.arange(size) + 0.5) * height / size - 0.5, 0, height - 1)
    xs = np.clip((np.arange(size) + 0.5) * width / size - 0.5, 0, width - 1)
    y0 = np.floor(ys).astype(np.int64)
    x0 = np.floor(xs).astype(np.int64)
    y1 = np.minimum(y0 + 1, height - 1)
    x1 = np.minimum(x0 + 1, width - 1)
    wy = (ys - y0)[:, None, None]
    wx = (xs - x0)[None, :, None]
    image = rgb.astype(np.float64)
    top = image[y0][:, x0] * (1 - wx) + image[y0][:, x1] * wx
    bottom = image[y1][:, x0] * (1 - wx) + image[y1][:, x1] * wx
    out: np.ndarray = (top * (1 - wy) + bottom * wy).astype(np.float32)
    return out


def preprocess(rgb: np.ndarray) -> np.ndarray:
    """The model's input tensor [1, S, S, 3] from an (H, W, 3) uint8 RGB photo."""
    if rgb.ndim != 3 or rgb.shape[2] != 3 or min(rgb.shape[:2]) < 1:
        raise ValueError(f"expected an (H, W, 3) RGB photo, got shape {rgb.shape}")
    return bilinear_resize(rgb)[None]


def box_iou(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """IoU of one box (4,) against boxes (N, 4)."""
    x1 = np.maximum(a[0], b[:, 0])
    y1 = np.maximum(a[1], b[:, 1])
    x2 = np.minimum(a[2], b[:, 2])
    y2 = np.minimum(a[3], b[:, 3])
    inter = np.clip(x2 - x1, 0, None) * np.clip(y2 - y1, 0, None)
    area_a = (a[2] - a[0]) * (a[3] - a[1])
    area_b = (b[:, 2] - b[:, 0]) * (b[:, 3] - b[:, 1])
    union = area_a + area_b - inter
    out: np.ndarray = np.where(union > 0, inter / np.where(union > 0, union, 1), 0.0)
    return out


def decode(
    raw: np.ndarray,
    width: int,
    height: int,
    model_classes: list[str],
    to_nyu40: list[str | None],
    score_threshold: float = SCORE_THRESHOLD,
) -> list[DetectedBox]:
    """The contract's decoding of a [1, MAX_DETECTIONS, 6] output for a W x H photo."""
    rows = np.asarray(raw, dtype=np.float64).reshape(-1, 6)
    scale = np.array([width, height, width, height]) / INPUT_SIZE
    kept: list[tuple[int, np.ndarray, float, str, str]] = []
    for index, row in enumerate(rows):
        score = float(row[4])
        class_index = round(float(row[5]))
        if not score >= score_threshold or not 0 <= class_index < len(model_classes):
            continue
        nyu = to_nyu40[class_index]
        if nyu is None:
            continue
        box = np.clip(row[:4] * scale, 0, [width, height, width, height])
        kept.append((index, box, score, nyu, model_classes[class_index]))
    kept.sort(key=lambda item: (-item[2], item[0]))
    chosen: list[tuple[int, np.ndarray, float, str, str]] = []
    for item in kept:
        same_class = [c[1] for c in chosen if c[3] == item[3]]
        if same_class and box_iou(item[1], np.array(same_class)).max() > NMS_IOU:
            continue
        chosen.append(item)
    return [
        DetectedBox(
            bbox=(float(box[0]), float(box[1]), float(box[2]), float(box[3])),
            score=score,
            cls=nyu,
            source_class=source,
        )
        for _, box, score, nyu, source in chosen
        if box[2] - box[0] >= MIN_BOX_PX and box[3] - box[1] >= MIN_BOX_PX
    ]


def read_metadata(model_dir: Path) -> dict[str, Any]:
    path = model_dir / METADATA_FILE
    try:
        metadata: dict[str, Any] = json.loads(path.read_text())
    except FileNotFoundError:
        raise DetectorModelError(f"no detector metadata at {path}") from None
    except (json.JSONDecodeError, UnicodeDecodeError) as error:
        raise DetectorModelError(f"detector metadata {path} is not JSON: {error}") from None
    space = metadata.get("label_space")
    classes = metadata.get("classes")
    if space not in LABEL_SPACES or not isinstance(classes, list) or not classes:
        raise DetectorModelError(
            f"detector metadata {path} needs label_space in {LABEL_SPACES} and a class list"
        )
    return metadata


class Detector:
    """One detector model, loaded once; `detect` gives NYU-40 boxes for a photo."""

    def __init__(self, model_dir: Path) -> None:
        self.model_dir = model_dir
        self.metadata = read_metadata(model_dir)
        self.classes: list[str] = [str(c) for c in self.metadata["classes"]]
        if self.metadata["label_space"] == "coco80":
            self.to_nyu40: list[str | None] = list(COCO_TO_NYU40)
        else:
            unknown = sorted(set(self.classes) - set(NYU40_CLASSES))
            if unknown:
                raise DetectorModelError(f"detector classes not in NYU-40: {unknown}")
            self.to_nyu40 = list(self.classes)
        if len(self.to_nyu40) != len(self.classes):
            raise DetectorModelError("the detector's class list does not match its label space")
        options = ort.SessionOptions()
        options.intra_op_num_threads = 1
        options.inter_op_num_threads = 1
        model_file = model_dir / MODEL_FILE
        try:
            self.session = ort.InferenceSession(
                str(model_file), options, providers=["CPUExecutionProvider"]
            )
        except Exception as error:  # onnxruntime raises its own untyped errors
            raise DetectorModelError(f"cannot load detector model {model_file}: {error}") from None
        inputs = {i.name: i.shape for i in self.session.get_inputs()}
        outputs = {o.name: o.shape for o in self.session.get_outputs()}
        if inputs.get(INPUT_NAME) != [1, INPUT_SIZE, INPUT_SIZE, 3] or outputs.get(OUTPUT_NAME) != [
            1,
            MAX_DETECTIONS,
            6,
        ]:
            raise DetectorModelError(
                f"detector model {model_file} has inputs {inputs} and outputs {outputs}; the "
                f"contract needs {INPUT_NAME} [1, {INPUT_SIZE}, {INPUT_SIZE}, 3] and "
                f"{OUTPUT_NAME} [1, {MAX_DETECTIONS}, 6]"
            )

    @classmethod
    def load(cls, model_dir: Path = DEFAULT_DETECTOR_DIR) -> Detector:
        model_file = model_dir / MODEL_FILE
        mtime = model_file.stat().st_mtime if model_file.exists() else 0.0
        return _cached_detector(model_dir.resolve(), mtime)

    def raw(self, tensor: np.ndarray) -> np.ndarray:
        out = self.session.run([OUTPUT_NAME], {INPUT_NAME: tensor})[0]
        return np.asarray(out, dtype=np.float32)

    def detect(
        self, rgb: np.ndarray, score_threshold: float = SCORE_THRESHOLD
    ) -> list[DetectedBox]:
        height, width = rgb.shape[:2]
        return decode(
            self.raw(preprocess(rgb)), width, height, self.classes, self.to_nyu40, score_threshold
        )


@lru_cache(maxsize=4)
def _cached_detector(model_dir: Path, mtime: float) -> Detector:
    # Keyed by modification time too, so a replaced file is loaded afresh.
    return Detector(model_dir)
