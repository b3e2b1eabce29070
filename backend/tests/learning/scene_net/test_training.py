"""Training the layout and object networks end to end on a few synthetic rooms: features
cached, the joint loss falls, the ONNX export matches PyTorch and the run time reads it."""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np
import pytest

torch = pytest.importorskip("torch")

from holiscene.learning.detector.backbone import FeatureExtractor  # noqa: E402
from holiscene.learning.detector.runtime import COCO_DETECTOR_DIR, MODEL_FILE  # noqa: E402
from holiscene.learning.scene_net.net import SceneNet, joint_loss  # noqa: E402
from holiscene.learning.scene_net.runtime import SceneNetwork  # noqa: E402
from holiscene.learning.scene_net.samples import room_samples  # noqa: E402
from holiscene.learning.scene_net.train import (  # noqa: E402
    SceneNetTrainConfig,
    _standardisation,
    batch_of,
    train_scene_net,
)
from holiscene.synth.generate import synthesize_to  # noqa: E402


@pytest.fixture(scope="module")
def rooms(tmp_path_factory: pytest.TempPathFactory) -> list[Path]:
    out = tmp_path_factory.mktemp("rooms")
    return [synthesize_to(seed, out) for seed in (900_010, 900_011, 900_012)]


def test_the_joint_loss_falls_on_a_few_rooms(rooms: list[Path], tmp_path: Path) -> None:
    extractor = FeatureExtractor(COCO_DETECTOR_DIR / MODEL_FILE, threads=2)
    samples = room_samples(extractor, rooms, tmp_path / "features", 0, True, progress=False)
    assert len(samples) == 3 and all(len(s.bbox) > 0 for s in samples)
    # A second read comes from the cache, the same arrays.
    again = room_samples(extractor, rooms, tmp_path / "features", 0, True, progress=False)
    assert np.array_equal(again[0].objects, samples[0].objects)
    assert len(list((tmp_path / "features").glob("*.npz"))) == 3

    torch.manual_seed(0)
    net = SceneNet(*_standardisation(samples), hidden=64)
    net.eval()  # no dropout: the same loss for the same weights
    batch = batch_of(samples)
    first, parts = joint_loss(net, batch)
    assert set(parts) == {"room", "objects", "corners_m", "violation_m"}
    optimiser = torch.optim.Adam(net.parameters(), lr=1e-3)
    for _ in range(60):
        loss, _ = joint_loss(net, batch)
        optimiser.zero_grad()
        loss.backward()
        optimiser.step()
    last, parts_after = joint_loss(net, batch)
    assert last.item() < 0.5 * first.item()
    assert parts_after["corners_m"] < parts["corners_m"]


def test_a_short_run_writes_a_model_the_run_time_reads(tmp_path: Path) -> None:
    config = SceneNetTrainConfig(
        rooms=4, validation_rooms=2, budget_s=6.0, batch=2, hidden=32, views=1
    )
    metrics = train_scene_net(tmp_path / "model", tmp_path / "cache", config)
    for name in ("model.onnx", "metadata.json", "metrics.json", "curve.png"):
        assert (tmp_path / "model" / name).is_file()
    assert metrics["export_max_difference"] < 1e-3
    assert json.loads((tmp_path / "model" / "metrics.json").read_text())["curve"]
    validation = metrics["validation"]
    assert 0.0 <= validation["layout_iou"] <= 1.0 and validation["pitch_mae_deg"] >= 0.0

    network = SceneNetwork(tmp_path / "model")
    from holiscene.inputs.validation import read_input_folder

    folder = next((tmp_path / "cache" / "rooms").iterdir())
    inputs = read_input_folder(folder, use_depth=False)
    assert inputs.ground_truth is not None and inputs.K is not None
    objects = inputs.ground_truth.objects
    estimate = network.estimate(inputs.photo.rgb, inputs.K, objects)
    assert set(estimate.objects) == {o.id for o in objects}
    assert estimate.room.corners_world().shape == (8, 3)
