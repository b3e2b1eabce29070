"""Evaluate a folder of predictions against a folder of ground-truth scenes."""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path

from holiscene_schema import Scene
from pydantic import ValidationError

from .metrics import Evaluation

PREDICTION_FILE = "scene.json"
TRUTH_FILE = "gt.json"


class EvaluationInputError(ValueError):
    pass


@dataclass
class EvaluationRun:
    evaluation: Evaluation
    missing_predictions: list[str]


def _load(path: Path) -> Scene:
    try:
        return Scene.model_validate_json(path.read_text())
    except (OSError, ValidationError) as exc:
        raise EvaluationInputError(f"{path} is not a valid scene: {exc}") from exc


def evaluate_folders(predictions: Path, truth: Path) -> EvaluationRun:
    """Pair `truth/<name>/gt.json` with `predictions/<name>/scene.json`.

    A ground-truth scene without a prediction counts as an empty prediction (everything wrong)
    and is listed, so a crashed pipeline cannot look better than a working one.
    """
    for folder in (predictions, truth):
        if not folder.is_dir():
            raise EvaluationInputError(f"{folder} is not a folder")
    truth_files = sorted(truth.glob(f"*/{TRUTH_FILE}"))
    if (truth / TRUTH_FILE).is_file():
        truth_files = [truth / TRUTH_FILE]
    if not truth_files:
        raise EvaluationInputError(f"{truth} holds no */{TRUTH_FILE}")
    evaluation = Evaluation()
    missing: list[str] = []
    for truth_file in truth_files:
        gt = _load(truth_file)
        name = truth_file.parent.name
        candidates = [predictions / name / PREDICTION_FILE, predictions / PREDICTION_FILE]
        pred_file = next((c for c in candidates if c.is_file()), None)
        if pred_file is None or (pred_file.parent == predictions and len(truth_files) > 1):
            missing.append(name)
            predicted = Scene(name=gt.name, image=gt.image)
        else:
            predicted = _load(pred_file)
        evaluation.add(predicted, gt)
    return EvaluationRun(evaluation, missing)
