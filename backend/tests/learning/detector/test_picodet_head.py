"""The NYU-40 class head on PicoDet's anchors: the taps are found in the committed graph and
line up with its anchors, the copies of its class branches give its own features, the targets
give each true box its best anchors, and a short training run exports one file of the detector
contract that agrees with PyTorch and leaves PicoDet as it was."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import onnx
import onnxruntime as ort
import pytest
import torch
from holiscene.learning.detector.data import BoxedPhoto, synthetic_photos
from holiscene.learning.detector.picodet_head import (
    PicoDetClassHead,
    ScoringHead,
    anchor_targets,
    class_branches,
    quality_focal_loss,
)
from holiscene.learning.detector.picodet_taps import PicoDetTaps, anchor_points, grid_sizes
from holiscene.learning.detector.picodet_train import PicoDetHeadConfig, train_picodet_head
from holiscene.learning.detector.runtime import (
    MODEL_FILE,
    PICODET_DETECTOR_DIR,
    Detector,
    preprocess,
)
from holiscene_schema.detector_model import INPUT_NAME
from onnx import TensorProto, helper

PICODET_MODEL = PICODET_DETECTOR_DIR / MODEL_FILE
SEEDS = range(932_000, 932_004)  # rooms no other training or benchmark uses


@pytest.fixture(scope="module")
def rooms(tmp_path_factory: pytest.TempPathFactory) -> list[BoxedPhoto]:
    return synthetic_photos(SEEDS, tmp_path_factory.mktemp("rooms"), workers=1)


def test_the_taps_line_up_with_the_anchors(rooms: list[BoxedPhoto]) -> None:
    tapped = PicoDetTaps(PICODET_MODEL)(preprocess(rooms[0].rgb))
    sizes = grid_sizes()
    assert [f.shape for f in tapped.branch_inputs] == [(96, c, c) for c in sizes]
    count = sum(c * c for c in sizes)
    assert tapped.boxes.shape == (count, 4)
    assert tapped.coco_scores.shape == (80, count)
    assert tapped.alignment.shape == (count,)
    assert tapped.alignment.min() >= 0 and tapped.alignment.max() <= 1
    # GFL's boxes are distances from the anchor's centre: every box holds its own centre,
    # which only holds when the centres are listed in the graph's order.
    points = anchor_points()
    assert np.all(points >= tapped.boxes[:, :2] - 1e-3)
    assert np.all(points <= tapped.boxes[:, 2:] + 1e-3)
    shuffled = points[::-1]
    assert not np.all(shuffled >= tapped.boxes[:, :2] - 1e-3)


def test_the_branch_copies_give_picodets_class_features(rooms: list[BoxedPhoto]) -> None:
    taps = PicoDetTaps(PICODET_MODEL)
    tensor = preprocess(rooms[1].rgb)
    model = onnx.load(str(PICODET_MODEL))
    for name in taps.names.features:
        model.graph.output.append(helper.make_tensor_value_info(name, TensorProto.FLOAT, None))
    session = ort.InferenceSession(model.SerializeToString(), providers=["CPUExecutionProvider"])
    expected = session.run(list(taps.names.features), {INPUT_NAME: tensor})
    copies = class_branches(taps.model, taps.names)
    with torch.no_grad():
        for copy, start, want in zip(copies, taps(tensor).branch_inputs, expected, strict=True):
            got = copy(torch.from_numpy(start[None])).numpy()
            assert got.shape == want.shape
            assert np.abs(got - want).max() < 1e-4 * max(1.0, float(np.abs(want).max()))
    # Their convolutions and batch norms' scales and shifts train; the statistics do not.
    trainable = sum(p.numel() for p in copies.parameters())
    assert 40_000 * 4 < trainable < 50_000 * 4


def test_each_true_box_takes_its_best_anchors() -> None:
    points = np.array([[15.0, 15.0], [20.0, 20.0], [80.0, 80.0], [25.0, 25.0]])
    anchors = np.array([
        [10.0, 10.0, 30.0, 30.0],  # the first true box exactly
        [12.0, 12.0, 50.0, 50.0],  # half of it, and most of the second
        [70.0, 70.0, 90.0, 90.0],  # away from both
        [20.0, 20.0, 60.0, 60.0],  # the second true box exactly
    ])  # fmt: skip
    truth = np.array([[10.0, 10.0, 30.0, 30.0], [20.0, 20.0, 60.0, 60.0]])
    target_class, target_iou = anchor_targets(anchors, points, truth, np.array([3, 5]))
    assert target_class.tolist()[0] == 3 and target_iou[0] == pytest.approx(1.0)
    assert target_class[3] == 5 and target_iou[3] == pytest.approx(1.0)
    assert target_class[2] == -1 and target_iou[2] == 0
    # The shared anchor goes to the box it meets better (IoU 0.69 against 0.28), if any.
    assert target_class[1] in (-1, 5)
    empty_class, empty_iou = anchor_targets(anchors, points, np.zeros((0, 4)), np.zeros(0))
    assert (empty_class == -1).all() and (empty_iou == 0).all()


def test_the_loss_rewards_the_target_quality() -> None:
    target_class = torch.tensor([[2, -1, -1]], dtype=torch.int16)
    target_iou = torch.tensor([[0.8, 0.0, 0.0]])
    right = torch.full((1, 3, 4), -6.0)
    right[0, 0, 2] = float(torch.logit(torch.tensor(0.8)))
    wrong = torch.full((1, 3, 4), -6.0)
    wrong[0, 0, 1] = 3.0
    assert quality_focal_loss(right, target_class, target_iou) < 0.5 * quality_focal_loss(
        wrong, target_class, target_iou
    )


def test_coco_only_classes_keep_cocos_scores() -> None:
    taps = PicoDetTaps(PICODET_MODEL)
    head = PicoDetClassHead(2, class_branches(taps.model, taps.names))
    scoring = ScoringHead(head, ["bed", "lamp"], ["bed", "person", "lamp"], 0.0).eval()
    count = sum(c * c for c in grid_sizes())
    branch_inputs = torch.zeros(1, 96, count)
    evidence = torch.zeros(1, count, 1 + 80)
    evidence[0, 7, 1 + 0] = 0.9  # COCO's "person" at anchor 7
    evidence[0, 7, 1 + 59] = 0.8  # COCO's "bed": weight 0, so the head alone decides
    with torch.no_grad():
        scores = scoring(branch_inputs, evidence)[0]
    assert scores.shape[0] == 3
    assert scores[1, 7] == pytest.approx(0.9)
    assert scores[0, 7] < 0.5


def test_an_unnamed_class_keeps_only_cocos_evidence() -> None:
    """The suggester does not name "books" itself (it calls patterned patches books): only
    COCO's "book" speaks for it."""
    taps = PicoDetTaps(PICODET_MODEL)
    head = PicoDetClassHead(2, class_branches(taps.model, taps.names))
    classes = ["bed", "books"]
    named = ScoringHead(head, classes, classes, 1.0).eval()
    unnamed = ScoringHead(head, classes, classes, 1.0, unnamed=("books",)).eval()
    count = sum(c * c for c in grid_sizes())
    branch_inputs = torch.randn(1, 96, count)
    evidence = torch.zeros(1, count, 1 + 80)
    evidence[0, 3, 1 + 73] = 0.6  # COCO's "book" at anchor 3
    with torch.no_grad():
        before, after = named(branch_inputs, evidence)[0], unnamed(branch_inputs, evidence)[0]
    assert torch.equal(before[0], after[0])  # bed: the head's, as before
    assert (before[1] > 0).all()  # the head's sigmoid speaks for books everywhere...
    assert after[1, 3] == pytest.approx(0.6)  # ...and now COCO alone does
    assert (torch.cat([after[1, :3], after[1, 4:]]) == 0).all()


def test_a_short_run_exports_one_faithful_model(tmp_path: Path, rooms: list[BoxedPhoto]) -> None:
    out = tmp_path / "head"
    before = PICODET_MODEL.read_bytes()
    metrics = train_picodet_head(
        rooms[:3], rooms[3:], PicoDetHeadConfig(epochs=1, batch=2, views=1), out
    )
    assert metrics["export_difference"] < 1e-4
    assert PICODET_MODEL.read_bytes() == before
    detector = Detector(out)
    assert detector.metadata["label_space"] == "nyu40"
    raw = detector.raw(preprocess(rooms[3].rgb))
    assert raw.shape == (1, 100, 6)
    # The classes the rooms hold, and those only COCO knows (people, toilets, bags).
    assert set(metrics["trained_classes"]) <= set(detector.classes)
    assert "person" in detector.classes and "person" not in metrics["trained_classes"]
    # One graph: PicoDet's own boxes and the head's scores meet in its NMS.
    ops = {node.op_type for node in onnx.load(str(out / MODEL_FILE)).graph.node}
    assert "NonMaxSuppression" in ops
