"""Helpers for the model registry and retraining tests: labelled scenes and model folders."""

from __future__ import annotations

import json
from functools import cache
from pathlib import Path

import cv2
import pytest
from holiscene.inputs import InputFiles, load_photo
from holiscene.store.scenes import SceneStore
from holiscene.synth.generate import synthesize
from holiscene_schema import Scene

# Seeds of labelled scenes the retraining tests store (no other test uses them).
LABELLED_SEEDS = (4101, 4102, 4103, 4104, 4105, 4106)


@cache
def _synthetic(seed: int) -> tuple[bytes, Scene]:
    synthetic = synthesize(seed)
    ok, png = cv2.imencode(".png", cv2.cvtColor(synthetic.frame.rgb, cv2.COLOR_RGB2BGR))
    assert ok
    return png.tobytes(), synthetic.truth


def store_labelled_scene(scenes: SceneStore, seed: int) -> str:
    """A synthetic scene with its true supports (set by a person: source 'manual')."""
    png, truth = _synthetic(seed)
    photo = load_photo(png)
    summary = scenes.create(InputFiles(photo=photo, K=None, detections=None), truth, "test")
    return summary.id


def store_unlabelled_scene(scenes: SceneStore, seed: int) -> str:
    """The same scene with the supports marked as the pipeline's guesses ('auto')."""
    png, truth = _synthetic(seed)
    auto = [s.model_copy(update={"source": "auto"}) for s in truth.supports]
    scene = truth.model_copy(update={"supports": auto})
    photo = load_photo(png)
    return scenes.create(InputFiles(photo=photo, K=None, detections=None), scene, "test").id


def fake_model_dir(folder: Path, payload: bytes = b"onnx-bytes", curve: bool = True) -> Path:
    """A model folder with stand-in file contents: the registry stores files, it does not
    read the network (the retraining tests use real models)."""
    folder.mkdir(parents=True, exist_ok=True)
    (folder / "model.onnx").write_bytes(payload)
    (folder / "metrics.json").write_text(json.dumps({"validation_accuracy": 0.5}))
    (folder / "data.json").write_text(json.dumps({"labelled_scenes": []}))
    (folder / "priors.json").write_text("{}")
    if curve:
        (folder / "curve.png").write_bytes(b"\x89PNG\r\n\x1a\n-curve")
    return folder


def needs_training() -> None:
    """Skip until the lead's training and ONNX runtime modules exist (they land separately)."""
    learning = Path(__file__).resolve().parents[2] / "src" / "holiscene" / "learning"
    missing = [n for n in ("train.py", "runtime.py") if not (learning / n).is_file()]
    if missing:
        pytest.skip(f"holiscene.learning lacks {', '.join(missing)}")
