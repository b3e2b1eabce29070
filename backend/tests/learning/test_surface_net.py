"""The Surface Network: the shipped model labels unseen synthetic rooms, a training run writes
a working model directory, and the CLI refuses bad arguments."""

from __future__ import annotations

import json
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest
from holiscene.geometry.surface_labels import MAP_SIZE, SURFACE_CLASSES, true_surface_map
from holiscene.geometry.surface_map import DEFAULT_SURFACE_MODEL, SurfaceModel
from holiscene.learning.surface_net import SurfaceTrainConfig, train_surface_model
from holiscene.synth.generate import synthesize

UNSEEN_SEEDS = range(4300, 4306)  # neither training (500000+) nor validation (510000+) rooms


def test_shipped_model_labels_unseen_rooms() -> None:
    model = SurfaceModel(DEFAULT_SURFACE_MODEL)
    right = total = 0
    for seed in UNSEEN_SEEDS:
        scene = synthesize(seed)
        probabilities = model.probabilities(scene.frame.rgb)
        assert probabilities.shape == (MAP_SIZE[0] * MAP_SIZE[1], len(SURFACE_CLASSES))
        assert np.allclose(probabilities.sum(axis=1), 1.0, atol=1e-4)
        truth = true_surface_map(scene.truth).ravel()
        right += int((probabilities.argmax(axis=1) == truth).sum())
        total += truth.size
    # 0.953 on the 100 validation rooms (metrics.json); the largest class covers about 0.4.
    assert right / total > 0.75


def test_a_mirrored_photo_gets_the_mirrored_labels() -> None:
    """The model averages the photo and its mirror image, so its answer is mirror-symmetric."""
    model = SurfaceModel(DEFAULT_SURFACE_MODEL)
    rgb = synthesize(UNSEEN_SEEDS[0]).frame.rgb
    shape = (MAP_SIZE[1], MAP_SIZE[0], len(SURFACE_CLASSES))
    plain = model.probabilities(rgb).reshape(shape)
    mirrored = model.probabilities(np.ascontiguousarray(rgb[:, ::-1])).reshape(shape)
    assert np.allclose(plain, mirrored[:, ::-1], atol=1e-4)


def test_training_writes_a_model_that_onnxruntime_runs(tmp_path: Path) -> None:
    config = SurfaceTrainConfig(
        train_seeds=(520_000, 4), validation_seeds=(520_100, 2), epochs=1, batch=2,
        cache_dir=tmp_path / "cache",
    )  # fmt: skip
    lines: list[str] = []
    metrics = train_surface_model(config, tmp_path / "model", lambda f, line: lines.append(line))
    assert metrics["onnx_max_difference"] < 1e-4
    assert lines[-1].startswith("done")
    written = json.loads((tmp_path / "model" / "metrics.json").read_text())
    assert written["classes"] == list(SURFACE_CLASSES)
    assert (tmp_path / "model" / "curve.png").read_bytes()[:4] == b"\x89PNG"
    model = SurfaceModel(tmp_path / "model" / "model.onnx")
    image = np.zeros((240, 320, 3), dtype=np.uint8)
    assert model.probabilities(image).shape == (MAP_SIZE[0] * MAP_SIZE[1], len(SURFACE_CLASSES))
    # The rendered rooms are cached: a second set-up reads them back.
    assert len(list((tmp_path / "cache").glob("*.npz"))) == 2


def test_cli_refuses_a_non_empty_output(tmp_path: Path) -> None:
    (tmp_path / "taken.txt").write_text("x")
    result = subprocess.run(
        [sys.executable, "-m", "holiscene.cli", "train-surfaces", "-o", str(tmp_path)],
        capture_output=True, text=True, check=False,
    )  # fmt: skip
    assert result.returncode == 2
    assert "not empty" in result.stderr


def test_missing_model_file_says_how_to_make_one(tmp_path: Path) -> None:
    with pytest.raises(FileNotFoundError, match="train-surfaces"):
        SurfaceModel(tmp_path / "none.onnx")
