"""The Relation Network at inference time: onnxruntime only, no PyTorch.

A model directory (the committed default, or one from the registry) holds the ONNX file and
the support priors counted with it; `SupportModel` loads both once and scores scenes.
"""

from __future__ import annotations

from collections.abc import Sequence
from functools import lru_cache
from pathlib import Path

import numpy as np
import onnxruntime as ort
from holiscene_schema.relation_model import INPUT_NAMES, OUTPUT_NAME

from .priors import SupportPriors
from .samples import NO_LABEL, SupportSample
from .training_api import MODEL_FILE, PRIORS_FILE

DEFAULT_MODEL_DIR = Path(__file__).resolve().parent / "default_model"


def softmax_rows(logits: np.ndarray) -> np.ndarray:
    """(N, N + 3, 2) logits -> the same shape of probabilities, each row summing to 1."""
    flat = logits.reshape(logits.shape[0], -1).astype(np.float64)
    flat = np.exp(flat - flat.max(axis=1, keepdims=True))
    probabilities: np.ndarray = (flat / flat.sum(axis=1, keepdims=True)).reshape(logits.shape)
    return probabilities


class SupportModel:
    def __init__(self, model_dir: Path) -> None:
        model_file = model_dir / MODEL_FILE
        if not model_file.is_file():
            raise FileNotFoundError(f"no Relation Network model at {model_file}")
        options = ort.SessionOptions()
        # The server runs one pipeline job at a time; one thread keeps its latency steady
        # and leaves the other core to the web server.
        options.intra_op_num_threads = 1
        options.inter_op_num_threads = 1
        self.model_dir = model_dir
        self.session = ort.InferenceSession(
            str(model_file), options, providers=["CPUExecutionProvider"]
        )
        self.priors = model_priors(model_dir)

    @classmethod
    def load(cls, model_dir: Path) -> SupportModel:
        return _cached_model(model_dir.resolve(), _mtime(model_dir / MODEL_FILE))

    def logits(self, inputs: dict[str, np.ndarray]) -> np.ndarray:
        out = self.session.run([OUTPUT_NAME], {k: inputs[k] for k in INPUT_NAMES})[0]
        return np.asarray(out, dtype=np.float32)

    def probabilities(self, inputs: dict[str, np.ndarray]) -> np.ndarray:
        return softmax_rows(self.logits(inputs))

    def accuracy(self, samples: Sequence[SupportSample]) -> float:
        """Share of labelled objects whose most probable answer is right (no tree decoding)."""
        right = total = 0
        for sample in samples:
            labelled = sample.targets != NO_LABEL
            answers = self.logits(sample.inputs).reshape(len(sample.targets), -1).argmax(1)
            right += int((answers[labelled] == sample.targets[labelled]).sum())
            total += int(labelled.sum())
        return right / total if total else 0.0


def model_priors(model_dir: Path) -> SupportPriors:
    """The support priors counted with a model (empty ones for a model without them)."""
    priors_file = model_dir / PRIORS_FILE
    return SupportPriors.load(priors_file) if priors_file.exists() else SupportPriors()


def _mtime(path: Path) -> float:
    return path.stat().st_mtime if path.exists() else 0.0


@lru_cache(maxsize=4)
def _cached_model(model_dir: Path, mtime: float) -> SupportModel:
    # Keyed by modification time too, so a replaced file is loaded afresh.
    return SupportModel(model_dir)
