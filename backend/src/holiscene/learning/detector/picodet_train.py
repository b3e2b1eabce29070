"""Train the NYU-40 class head on PicoDet's anchors (`picodet_head.py`; PyTorch).

Each training photo is randomised once per view (data.randomise) and run through the wrapped
PicoDet once (onnxruntime) up to its taps; the anchors' inputs and fixed targets are cached,
so an epoch costs the small head alone. The best epoch by validation mAP@0.5 is kept and
exported with PicoDet as one ONNX file of the detector contract, with metadata.json,
metrics.json and curve.png.
"""

from __future__ import annotations

import time
from collections.abc import Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np
import onnx
import onnxruntime as ort
import torch
from holiscene_schema.detector_model import INPUT_NAME
from onnx import TensorProto, helper

from ..training_api import TrainProgress
from .data import BoxedPhoto, classes_in, randomise
from .epoch_record import EpochRecord
from .picodet_head import (
    EVIDENCE_CHANNELS,
    HEAD_SCORES,
    PicoDetClassHead,
    ScoringHead,
    anchor_targets,
    class_branches,
    export_picodet_head,
    nms_rows,
    quality_focal_loss,
)
from .picodet_taps import (
    FEATURE_CHANNELS,
    NmsSettings,
    PicoDetTaps,
    TappedAnchors,
    anchor_points,
)
from .runtime import MODEL_FILE, PICODET_DETECTOR_DIR, preprocess
from .train import FeatureSet, final_classes, optimiser_with_copies, score_raw

HEAD_FILE = "head.pt"


def tap_inputs(tapped: TappedAnchors) -> tuple[np.ndarray, np.ndarray]:
    """One photo's taps as the head reads them: branch inputs [96, N] and evidence
    [N, EVIDENCE_CHANNELS] (alignment, COCO's scores)."""
    branches = np.concatenate([f.reshape(f.shape[0], -1) for f in tapped.branch_inputs], axis=1)
    evidence = np.concatenate([tapped.alignment[None], tapped.coco_scores], axis=0).T
    return branches, evidence


@dataclass(frozen=True)
class PicoDetHeadConfig:
    seed: int = 0
    epochs: int = 20
    batch: int = 16
    learning_rate: float = 3e-3
    hidden: int = 96
    coco_weight: float = 1.0  # 0: the head alone for the classes it learned
    # Classes the exported head does not name (learned all the same; COCO's evidence stays):
    # the scene page's suggester leaves out "books", which it puts on every patterned patch of
    # a real photo (docs/detector.md).
    unnamed: tuple[str, ...] = ()
    views: int = 2  # randomised views of each training photo
    # The copies of PicoDet's class branches learn at this share of the head's rate: they
    # start trained, the head does not.
    branch_learning_rate: float = 0.1
    picodet_model: Path = PICODET_DETECTOR_DIR / MODEL_FILE


@dataclass
class AnchorSet:
    """Every photo's anchors: the head's inputs, fixed targets, and for scoring the boxes."""

    branches: np.ndarray  # (P, 96, N) float16: the class branches' inputs
    evidence: np.ndarray  # (P, N, EVIDENCE_CHANNELS) float16
    target_class: np.ndarray  # (P, N) int16, -1 background
    target_iou: np.ndarray  # (P, N) float16
    boxes: np.ndarray  # (P, N, 4) float32, the 512-pixel input
    scoring: FeatureSet  # the photos' true boxes and sizes, as score_raw reads them


def extract_anchors(
    photos: Sequence[BoxedPhoto],
    classes: list[str],
    taps: PicoDetTaps,
    rng: np.random.Generator | None,
    say: TrainProgress,
    label: str,
    share: tuple[float, float],
) -> AnchorSet:
    """Run PicoDet to its taps on each photo (randomised first when `rng` is given)."""
    index_of = {c: i for i, c in enumerate(classes)}
    points = anchor_points()
    count = len(points)
    anchors = AnchorSet(
        branches=np.zeros((len(photos), FEATURE_CHANNELS, count), np.float16),
        evidence=np.zeros((len(photos), count, EVIDENCE_CHANNELS), np.float16),
        target_class=np.full((len(photos), count), -1, np.int16),
        target_iou=np.zeros((len(photos), count), np.float16),
        boxes=np.zeros((len(photos), count, 4), np.float32),
        scoring=FeatureSet(features=np.zeros(0, np.float16), coco=None),
    )
    for n, original in enumerate(photos):
        photo = randomise(original, rng) if rng is not None else original
        tapped = taps(preprocess(photo.rgb))
        anchors.branches[n], anchors.evidence[n] = tap_inputs(tapped)
        anchors.boxes[n] = tapped.boxes
        truth, truth_class = anchors.scoring.add_truth(photo, index_of)
        anchors.target_class[n], anchors.target_iou[n] = anchor_targets(
            tapped.boxes, points, truth, truth_class
        )
        if n % 20 == 0 or n == len(photos) - 1:
            done = share[0] + (share[1] - share[0]) * (n + 1) / len(photos)
            say(done, f"{label}: anchors {n + 1}/{len(photos)}")
    return anchors


def _tensors(data: AnchorSet, index: np.ndarray | slice) -> tuple[torch.Tensor, torch.Tensor]:
    return (
        torch.from_numpy(data.branches[index].astype(np.float32)),
        torch.from_numpy(data.evidence[index].astype(np.float32)),
    )


def validation_map(
    scoring: ScoringHead,
    data: AnchorSet,
    classes: list[str],
    trained: list[str],
    nms: NmsSettings,
) -> tuple[float, Any]:
    """mAP@0.5 over the trained classes (PicoDet's NMS and the contract's decoding)."""
    with torch.no_grad():
        raw = (
            nms_rows(data.boxes[n], scoring(*_tensors(data, slice(n, n + 1)))[0].numpy(), nms)
            for n in range(len(data.branches))
        )
        return score_raw(raw, data.scoring, classes, set(trained))


def train_picodet_head(
    train_photos: Sequence[BoxedPhoto],
    validation_photos: Sequence[BoxedPhoto],
    config: PicoDetHeadConfig,
    out_dir: Path,
    progress: TrainProgress | None = None,
) -> dict[str, Any]:
    say = progress or (lambda fraction, line: None)
    started = time.perf_counter()
    torch.manual_seed(config.seed)
    rng = np.random.default_rng(config.seed)
    trained = classes_in(train_photos)
    classes = final_classes(trained)
    taps = PicoDetTaps(config.picodet_model)
    views = [p for p in train_photos for _ in range(config.views)]
    train = extract_anchors(views, trained, taps, rng, say, "training photos", (0, 0.2))
    validation = extract_anchors(
        validation_photos, trained, taps, None, say, "validation", (0.2, 0.25)
    )
    head = PicoDetClassHead(len(trained), class_branches(taps.model, taps.names), config.hidden)
    steps = -(-len(views) // config.batch)
    optimiser, schedule = optimiser_with_copies(
        head,
        list(head.branches.parameters()),
        config.learning_rate,
        config.branch_learning_rate,
        steps * config.epochs,
    )
    record = EpochRecord(head, started)
    for epoch in range(1, config.epochs + 1):
        head.train()
        total = 0.0
        order = rng.permutation(len(views))
        for start in range(0, len(views), config.batch):
            index = np.sort(order[start : start + config.batch])
            logits = head(*_tensors(train, index))
            loss = quality_focal_loss(
                logits,
                torch.from_numpy(train.target_class[index]),
                torch.from_numpy(train.target_iou[index].astype(np.float32)),
            )
            optimiser.zero_grad()
            loss.backward()  # type: ignore[no-untyped-call]
            optimiser.step()
            schedule.step()
            total += loss.item() * len(index)
        head.eval()
        score, _ = validation_map(
            ScoringHead(head, trained, classes, 0.0), validation, classes, trained, taps.nms
        )
        say(0.25 + 0.75 * epoch / config.epochs, record.add(epoch, total / len(views), score))
    record.keep_best()
    rules = {
        weight: validation_map(
            ScoringHead(head, trained, classes, weight), validation, classes, trained, taps.nms
        )[1].summary(set(trained))
        for weight in (0.0, config.coco_weight)
    }
    out_dir.mkdir(parents=True, exist_ok=True)
    torch.save({"state": head.state_dict(), "trained": trained}, out_dir / HEAD_FILE)
    scoring = ScoringHead(head, trained, classes, config.coco_weight, config.unnamed).eval()
    export_picodet_head(scoring, taps.model, taps.names, out_dir / MODEL_FILE)
    difference = _export_difference(scoring, taps, out_dir / MODEL_FILE, validation_photos[0])
    metrics = {
        "classes": classes,
        "trained_classes": trained,
        "validation_by_rule": {str(w): s for w, s in rules.items()},
        "train_photos": len(train_photos),
        "validation_photos": len(validation_photos),
        "export_difference": difference,
    }
    metadata = {
        "name": "NYU-40 detector (COCO PicoDet's boxes, a class head trained on synthetic rooms)",
        "label_space": "nyu40",
        "classes": classes,
        "coco_weight": config.coco_weight,
        "unnamed": list(config.unnamed),
        "provenance": {
            "backbone": "the COCO PicoDet of ../picodet_detector (see its metadata.json)",
            "head": "trained by holiscene train-detector --on-picodet on the photos in "
            "metrics.json",
        },
    }
    return record.write_files(out_dir, config, metrics, metadata)


def _export_difference(
    scoring: ScoringHead, taps: PicoDetTaps, model_path: Path, photo: BoxedPhoto
) -> float:
    """The largest difference between the exported model's anchor scores and PyTorch's on
    one photo."""
    model = onnx.load(str(model_path))
    model.graph.output.append(helper.make_tensor_value_info(HEAD_SCORES, TensorProto.FLOAT, None))
    session = ort.InferenceSession(model.SerializeToString(), providers=["CPUExecutionProvider"])
    tensor = preprocess(photo.rgb)
    exported = np.asarray(session.run([HEAD_SCORES], {INPUT_NAME: tensor})[0])
    with torch.no_grad():
        branches, evidence = tap_inputs(taps(tensor))
        reference = scoring(
            torch.from_numpy(branches[None]), torch.from_numpy(evidence[None])
        ).numpy()
    return float(np.abs(exported - reference).max())
