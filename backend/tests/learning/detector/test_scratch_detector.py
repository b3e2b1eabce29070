"""The detector trained from scratch: its net halves the contract's input as the training data
is halved, its ONNX export is a detector of the contract that the runtime loads, and a short
real training run (on rooms the generator renders) writes the model directory, stopping when
its wall-clock budget is spent."""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np
import pytest
import torch
from holiscene.learning.detector.data import BoxedPhoto, synthetic_photos
from holiscene.learning.detector.runtime import Detector, preprocess
from holiscene.learning.detector.scratch_net import (
    CELLS,
    NET_SIZE,
    ScratchDetector,
    ScratchNet,
    export_scratch_detector,
    halve,
)
from holiscene.learning.detector.scratch_train import (
    ScratchTrainConfig,
    _learning_rate,
    train_scratch_detector,
)
from holiscene_schema.detector_model import INPUT_SIZE, MAX_DETECTIONS

# Seeds no other training or benchmark uses.
SEEDS = range(930_000, 930_006)


@pytest.fixture(scope="module")
def rooms(tmp_path_factory: pytest.TempPathFactory) -> list[BoxedPhoto]:
    return synthetic_photos(SEEDS, tmp_path_factory.mktemp("rooms"), workers=1)


def test_halve_is_the_graphs_first_step() -> None:
    images = np.random.default_rng(0).uniform(0, 255, (1, INPUT_SIZE, INPUT_SIZE, 3))
    images = images.astype(np.float32)
    pooled = torch.nn.functional.avg_pool2d(torch.from_numpy(images).permute(0, 3, 1, 2), 2)
    assert halve(images).shape == (1, 3, NET_SIZE, NET_SIZE)
    assert np.abs(halve(images) - pooled.numpy()).max() < 1e-4


def test_net_and_detector_shapes() -> None:
    net = ScratchNet(5).eval()
    with torch.no_grad():
        logits, sides = net(torch.full((2, 3, NET_SIZE, NET_SIZE), 128.0))
        raw = ScratchDetector(net)(torch.zeros((1, INPUT_SIZE, INPUT_SIZE, 3)))
    assert logits.shape == (2, 5, CELLS, CELLS)
    assert sides.shape == (2, 4, CELLS, CELLS) and bool((sides > 0).all())
    assert raw.shape == (1, MAX_DETECTIONS, 6)
    assert set(raw[0, :, 5].tolist()) <= {0.0, 1.0, 2.0, 3.0, 4.0}


def test_export_is_a_detector_the_runtime_loads(tmp_path: Path, rooms: list[BoxedPhoto]) -> None:
    torch.manual_seed(1)
    classes = ["chair", "table", "lamp"]
    example = preprocess(rooms[0].rgb)
    difference = export_scratch_detector(ScratchNet(len(classes)), example, tmp_path / "model.onnx")
    assert difference < 1e-3
    metadata = {"name": "untrained", "label_space": "nyu40", "classes": classes}
    (tmp_path / "metadata.json").write_text(json.dumps(metadata))
    detector = Detector(tmp_path)
    assert detector.raw(example).shape == (1, MAX_DETECTIONS, 6)
    found = detector.detect(rooms[0].rgb, 0.0)
    assert found and {d.cls for d in found} <= set(classes)


def test_learning_rate_warms_up_then_anneals_to_zero() -> None:
    config = ScratchTrainConfig(learning_rate=1.0)
    rates = [_learning_rate(config, done) for done in (0.0, 0.03, 0.5, 1.0)]
    assert rates[0] < rates[1] and rates[1] > rates[2] > rates[3]
    assert rates[3] == pytest.approx(0.0)


def test_training_writes_a_model_directory(tmp_path: Path, rooms: list[BoxedPhoto]) -> None:
    out = tmp_path / "scratch"
    config = ScratchTrainConfig(epochs=2, batch=2, views=1, threads=1)
    lines: list[str] = []
    metrics = train_scratch_detector(
        rooms[:4], rooms[4:], config, out, lambda fraction, line: lines.append(line)
    )
    assert sorted(p.name for p in out.iterdir()) == [
        "curve.png", "metadata.json", "metrics.json", "model.onnx",
    ]  # fmt: skip
    assert [c["epoch"] for c in metrics["curve"]] == [1, 2]
    assert any(line.startswith("epoch 2:") for line in lines)
    metadata = json.loads((out / "metadata.json").read_text())
    assert metadata["label_space"] == "nyu40"
    assert metadata["classes"] == metrics["classes"]
    assert set(metrics["classes"]) == {c for p in rooms[:4] for c in p.classes}
    assert "/" not in json.dumps(metrics["config"])  # no machine's paths in a committed file
    assert Detector(out).detect(rooms[4].rgb, 0.0)


def test_training_stops_when_its_time_is_spent(tmp_path: Path, rooms: list[BoxedPhoto]) -> None:
    config = ScratchTrainConfig(epochs=50, batch=2, views=1, threads=1, time_budget_s=1e-3)
    metrics = train_scratch_detector(rooms[:4], rooms[4:], config, tmp_path / "out")
    assert len(metrics["curve"]) == 1
    assert (tmp_path / "out" / "model.onnx").is_file()
