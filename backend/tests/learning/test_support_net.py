"""The default Relation Network: shapes, masking, ONNX export and training."""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np
import onnxruntime as ort
import pytest

torch = pytest.importorskip("torch", reason="the train extra (PyTorch) is not installed")

from holiscene.learning.export import EXPORT_TOLERANCE, export_onnx  # noqa: E402
from holiscene.learning.nets import MASKED, SupportNet  # noqa: E402
from holiscene.learning.preprocess import relation_inputs  # noqa: E402
from holiscene.learning.runtime import SupportModel  # noqa: E402
from holiscene.learning.samples import SupportSample, answer_index  # noqa: E402
from holiscene.learning.train import (  # noqa: E402
    accuracy,
    augment,
    scene_loss,
    train_relation_model,
)
from holiscene.learning.training_api import (  # noqa: E402
    CURVE_FILE,
    DATA_FILE,
    METRICS_FILE,
    MODEL_FILE,
    PRIORS_FILE,
    TrainConfig,
)


def tabletop(seed: int, n_boxes: int = 2) -> SupportSample:
    """A table on the floor with boxes on it, drawn as rectangles on a noisy photo."""
    rng = np.random.default_rng(seed)
    image = rng.integers(0, 255, (120, 160, 3), dtype=np.uint8)
    table = (40.0, 70.0, 130.0, 110.0)
    boxes = [table]
    for k in range(n_boxes):
        x0 = 45.0 + 40 * k + rng.integers(0, 8)
        boxes.append((x0, 45.0, x0 + 25, 70.0))
    masks = []
    for x0, y0, x1, y1 in boxes:
        mask = np.zeros((120, 160), dtype=bool)
        mask[int(y0) : int(y1), int(x0) : int(x1)] = True
        masks.append(mask)
    classes = ["table"] + ["box"] * n_boxes
    n = len(classes)
    targets = [answer_index(n + 1, "below")] + [answer_index(0, "below")] * n_boxes
    ids = tuple(f"o{i}" for i in range(n))
    inputs = relation_inputs(image, masks, boxes, classes)
    return SupportSample(f"tabletop-{seed}", inputs, ids, tuple(classes), np.array(targets))


def test_output_shape_and_self_support_is_masked() -> None:
    sample = tabletop(0, n_boxes=3)
    net = SupportNet().eval()
    with torch.no_grad():
        logits = net(**{k: torch.from_numpy(v) for k, v in sample.inputs.items()})
    assert logits.shape == (4, 4 + 3, 2)
    for i in range(4):
        assert torch.all(logits[i, i] == MASKED)


def test_a_single_object_scene_works() -> None:
    sample = tabletop(1, n_boxes=0)
    with torch.no_grad():
        logits = SupportNet().eval()(**{k: torch.from_numpy(v) for k, v in sample.inputs.items()})
    assert logits.shape == (1, 4, 2)


def test_onnx_export_matches_pytorch_for_any_object_count(tmp_path: Path) -> None:
    net = SupportNet().eval()
    difference = export_onnx(net, tabletop(2), tmp_path / "m.onnx")
    assert difference <= EXPORT_TOLERANCE
    session = ort.InferenceSession(str(tmp_path / "m.onnx"))
    other = tabletop(3, n_boxes=4)  # another object count than the export example
    got = session.run(None, other.inputs)[0]
    with torch.no_grad():
        expected = net(**{k: torch.from_numpy(v) for k, v in other.inputs.items()}).numpy()
    assert np.abs(got - expected).max() <= EXPORT_TOLERANCE


def test_a_few_steps_lower_the_loss() -> None:
    torch.manual_seed(0)
    samples = [tabletop(s) for s in range(4)]
    net = SupportNet()
    optimiser = torch.optim.Adam(net.parameters(), lr=3e-3)
    tensors = [{k: torch.from_numpy(v) for k, v in s.inputs.items()} for s in samples]

    def total() -> float:
        net.eval()
        with torch.no_grad():
            return sum(float(scene_loss(net, s, t)) for s, t in zip(samples, tensors, strict=True))

    before = total()
    for _ in range(15):
        net.train()
        optimiser.zero_grad()
        for s, t in zip(samples, tensors, strict=True):
            scene_loss(net, s, t).backward()
        optimiser.step()
    assert total() < 0.5 * before
    assert accuracy(net, samples) == 1.0


def test_mirroring_keeps_boxes_valid() -> None:
    import random

    sample = tabletop(4)
    tensors = {k: torch.from_numpy(v) for k, v in sample.inputs.items()}
    for seed in range(6):
        out = augment(tensors, random.Random(seed))
        assert torch.all(out["boxes"][:, 2] >= out["boxes"][:, 0])
        assert out["image"].min() >= 0 and out["image"].max() <= 1


def test_training_writes_a_complete_model_directory(tmp_path: Path) -> None:
    labelled = [tabletop(s) for s in range(6)]
    config = TrainConfig(synthetic_scenes=0, max_epochs=2, patience=2, cache_dir=tmp_path / "c")
    lines: list[str] = []
    result = train_relation_model(
        config, labelled, tmp_path / "model", lambda _, line: lines.append(line)
    )
    for name in (MODEL_FILE, METRICS_FILE, PRIORS_FILE, DATA_FILE, CURVE_FILE):
        assert (result.model_dir / name).is_file(), name
    metrics = json.loads((result.model_dir / METRICS_FILE).read_text())
    assert metrics["epochs"] == 2 and len(metrics["curve"]) == 2
    assert json.loads((result.model_dir / DATA_FILE).read_text())["labelled_scenes"] == [
        s.name for s in labelled
    ]
    assert any("epoch 2" in line for line in lines)
    model = SupportModel.load(result.model_dir)
    assert 0.0 <= model.accuracy(labelled) <= 1.0
    assert model.priors.counts["box"] == {"table|below": 10.0}


def test_training_without_labels_is_refused(tmp_path: Path) -> None:
    config = TrainConfig(synthetic_scenes=0, cache_dir=tmp_path)
    with pytest.raises(ValueError, match="no labelled objects"):
        train_relation_model(config, [], tmp_path / "model")
