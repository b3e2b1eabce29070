"""Fine-tune an NYU-40 detector head on the COCO detector's frozen features (PyTorch).

`holiscene train-detector` calls `train_detector`. Each training photo is randomised once
(data.randomise) and passed through the frozen COCO backbone once (onnxruntime); the head then
trains on random windows of those feature maps (the neck's and the deep ones, aligned), so an
epoch costs the head alone (and, with `tune_deep_blocks`, the head's own copy of the
backbone's stride-32 blocks, run from the cached features at a 16th of the input). The best
epoch by validation mAP@0.5 is kept, exported with the backbone as one ONNX file of the
detector contract, and written with metadata.json, metrics.json and curve.png.
"""

from __future__ import annotations

import time
from collections.abc import Callable, Iterable, Sequence
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np
import torch
from holiscene_schema import NYU40_CLASSES
from holiscene_schema.detector_model import COCO_TO_NYU40, INPUT_SIZE

from ...evaluation.detection_2d import MAP_SCORE_THRESHOLD, DetectionEvaluation, ScoredBox
from ...synth.plan import RoomStyle
from ..training_api import TrainProgress
from .backbone import DEEP_STRIDE, FeatureExtractor, box_head_weights
from .data import BoxedPhoto, center_targets, classes_in, randomise
from .epoch_record import EpochRecord
from .net import STRIDE, DetectorHead, ExportedHead, deep_blocks, export_detector
from .runtime import COCO_DETECTOR_DIR, MODEL_FILE, decode, preprocess

CELLS = INPUT_SIZE // STRIDE
DEEP_SCALE = DEEP_STRIDE // STRIDE  # neck cells per deep cell along each side
HEAD_FILE = "head.pt"


@dataclass(frozen=True)
class DetectorTrainConfig:
    seed: int = 0
    epochs: int = 24
    batch: int = 16
    window: int = 64  # feature cells per side of each training window
    learning_rate: float = 3e-3
    hidden: int = 96
    coco_weight: float = 1.0  # 0: the new head alone for every class
    views: int = 1  # randomised views of each training photo
    # Fine-tune a copy of the backbone's stride-32 blocks for the head (docs/detector.md),
    # at a fraction of the head's learning rate: they start trained, the head does not.
    tune_deep_blocks: bool = False
    deep_blocks_learning_rate: float = 0.1
    retexture: float = 0.0  # chance that a synthetic object is repainted (retexture.py)
    # The training rooms' style (synth/plan.py RoomStyle): the caller renders them.
    cushion_rows: bool = False
    coco_model: Path = COCO_DETECTOR_DIR / MODEL_FILE

    @property
    def room_style(self) -> RoomStyle:
        """The style the training rooms are rendered in."""
        return RoomStyle(cushion_rows=self.cushion_rows)


# Input tensor [1, S, S, 3] -> (what the trained net reads, the COCO heatmap, the deep
# features or None), batch of one.
Encoder = Callable[[np.ndarray], tuple[np.ndarray, np.ndarray, np.ndarray | None]]


@dataclass
class FeatureSet:
    features: np.ndarray  # (N, ...) float16: the backbone's (128, CELLS, CELLS), or an image
    coco: np.ndarray | None  # (N, 80, CELLS, CELLS) float16, validation only
    # The deep branch's input, when encoded, float16: the deep features (N, 480, CELLS / 8,
    # CELLS / 8) or the features at a 16th of the input (N, 88, CELLS / 4, CELLS / 4).
    deep: np.ndarray | None = None
    boxes: list[np.ndarray] = field(default_factory=list)  # input pixels, per sample
    class_index: list[np.ndarray] = field(default_factory=list)
    photo_boxes: list[list[ScoredBox]] = field(default_factory=list)  # photo pixels
    photo_sizes: list[tuple[int, int]] = field(default_factory=list)  # (width, height)

    def add_truth(
        self, photo: BoxedPhoto, index_of: dict[str, int]
    ) -> tuple[np.ndarray, np.ndarray]:
        """Keep the photo's boxes of the classes in `index_of`: in input pixels with their
        class indices (for targets; also returned), and in photo pixels (for scoring)."""
        height, width = photo.rgb.shape[:2]
        known = [i for i, c in enumerate(photo.classes) if c in index_of]
        scale = np.array([INPUT_SIZE / width, INPUT_SIZE / height] * 2)
        boxes = photo.boxes[known] * scale if known else np.zeros((0, 4))
        class_index = np.array([index_of[photo.classes[i]] for i in known], np.int64)
        self.boxes.append(boxes)
        self.class_index.append(class_index)
        self.photo_boxes.append([ScoredBox(_box(photo.boxes[i]), photo.classes[i]) for i in known])
        self.photo_sizes.append((width, height))
        return boxes, class_index


def model_name(config: DetectorTrainConfig) -> str:
    """What the model is, for people choosing one (the models page, the benchmark)."""
    tuned = "head and a copy of its stride-32 blocks" if config.tune_deep_blocks else "head"
    extras = [
        *(["rows of cushions"] if config.cushion_rows else []),
        *(["repainted surfaces"] if config.retexture > 0 else []),
    ]
    rooms = "synthetic rooms" + (f" with {' and '.join(extras)}" if extras else "")
    return f"NYU-40 detector (COCO backbone, {tuned} fine-tuned on {rooms})"


def final_classes(trained: Sequence[str]) -> list[str]:
    """The model's class list: the classes it learned and those COCO knows, NYU-40 order."""
    known = set(trained) | {c for c in COCO_TO_NYU40 if c is not None}
    return [c for c in NYU40_CLASSES if c in known]


def extract(
    photos: Sequence[BoxedPhoto],
    classes: list[str],
    extractor: Encoder,
    rng: np.random.Generator | None,
    keep_coco: bool,
    say: TrainProgress,
    label: str,
    retexture: float = 0.0,
    share: tuple[float, float] = (0.0, 0.0),
) -> FeatureSet:
    """What `extractor` makes of each photo (randomised first when `rng` is given): the
    backbone's features, or for a net trained from scratch its input. `share`: the part of
    the run's progress this extraction covers, from and to."""
    index_of = {c: i for i, c in enumerate(classes)}
    feature_set = FeatureSet(features=np.zeros(0, np.float16), coco=None)
    for n, original in enumerate(photos):
        photo = randomise(original, rng, retexture) if rng is not None else original
        features, coco, deep = extractor(preprocess(photo.rgb))
        if n == 0:  # sized by the first sample: the extractor decides the shapes
            feature_set.features = np.zeros((len(photos), *features.shape[1:]), np.float16)
            if keep_coco:
                feature_set.coco = np.zeros((len(photos), *coco.shape[1:]), np.float16)
            if deep is not None:
                feature_set.deep = np.zeros((len(photos), *deep.shape[1:]), np.float16)
        feature_set.features[n] = features[0]
        if feature_set.deep is not None and deep is not None:
            feature_set.deep[n] = deep[0]
        if feature_set.coco is not None:
            feature_set.coco[n] = coco[0]
        feature_set.add_truth(photo, index_of)
        if n % 20 == 0 or n == len(photos) - 1:
            done = share[0] + (share[1] - share[0]) * (n + 1) / len(photos)
            say(done, f"{label}: features {n + 1}/{len(photos)}")
    return feature_set


def _box(row: np.ndarray) -> tuple[float, float, float, float]:
    return float(row[0]), float(row[1]), float(row[2]), float(row[3])


def focal_loss(logits: torch.Tensor, target: torch.Tensor) -> torch.Tensor:
    """CenterNet's penalty-reduced focal loss, per object."""
    p = torch.sigmoid(logits).clamp(1e-4, 1 - 1e-4)
    positive = target.eq(1).float()
    pos = -torch.log(p) * (1 - p) ** 2 * positive
    neg = -torch.log(1 - p) * p**2 * (1 - target) ** 4 * (1 - positive)
    return (pos.sum() + neg.sum()) / positive.sum().clamp(min=1)


def box_loss(predicted: torch.Tensor, target: torch.Tensor) -> torch.Tensor:
    """GIoU loss of boxes given as sides about one point, plus a little L1."""
    pl, pt, pr, pb = predicted.unbind(1)
    tl, tt, tr, tb = target.unbind(1)
    inter = (torch.minimum(pl, tl) + torch.minimum(pr, tr)).clamp(min=0) * (
        torch.minimum(pt, tt) + torch.minimum(pb, tb)
    ).clamp(min=0)
    union = (pl + pr) * (pt + pb) + (tl + tr) * (tt + tb) - inter
    hull = (torch.maximum(pl, tl) + torch.maximum(pr, tr)) * (
        torch.maximum(pt, tt) + torch.maximum(pb, tb)
    )
    giou = inter / union.clamp(min=1e-6) - (hull - union) / hull.clamp(min=1e-6)
    return (1 - giou).mean() + 0.01 * (predicted - target).abs().mean()


def detection_loss(
    logits: torch.Tensor,
    sides: torch.Tensor,
    heatmaps: torch.Tensor,
    cells: list[tuple[int, int, int]],
    target_sides: torch.Tensor,
) -> torch.Tensor:
    """Focal loss on the class heatmaps plus the box loss at the objects' centre cells
    (sample, row, column)."""
    loss = focal_loss(logits, heatmaps)
    if cells:
        b, r, c = (torch.tensor(v) for v in zip(*cells, strict=True))
        loss = loss + box_loss(sides[b, :, r, c], target_sides)
    return loss


def score_raw(
    raw_outputs: Iterable[np.ndarray], data: FeatureSet, classes: list[str], scored: set[str]
) -> tuple[float, DetectionEvaluation]:
    """mAP@0.5 over the `scored` classes of a model's raw outputs (one per photo of `data`,
    the contract's decoding down to the mAP threshold), and the whole evaluation."""
    evaluation = DetectionEvaluation(iou=0.5)
    for n, raw in enumerate(raw_outputs):
        width, height = data.photo_sizes[n]
        found = decode(raw, width, height, classes, list(classes), MAP_SCORE_THRESHOLD)
        evaluation.add([ScoredBox(d.bbox, d.cls, d.score) for d in found], data.photo_boxes[n])
    summary = evaluation.summary(scored)
    return float(summary["map"] or 0.0), evaluation


@dataclass
class Batch:
    features: torch.Tensor  # windows of the neck's features
    deep_input: torch.Tensor  # the deep branch's input, whole photos
    deep_windows: list[tuple[int, int]]  # each window's first deep cell (row, column)
    heatmaps: torch.Tensor
    cells: list[tuple[int, int, int]]  # objects' centre cells as (sample, row, column)
    target_sides: torch.Tensor

    def deep_features(self, head: DetectorHead, window: int) -> torch.Tensor:
        """The head's deep features over the windows (computed on whole photos first)."""
        deep = head.deep_features(self.deep_input)
        span = window // DEEP_SCALE
        return torch.stack([
            deep[b, :, dy : dy + span, dx : dx + span]
            for b, (dy, dx) in enumerate(self.deep_windows)
        ])  # fmt: skip


def _batch(
    data: FeatureSet, index: np.ndarray, window: int, num_classes: int, rng: np.random.Generator
) -> Batch:
    """Features and targets of random windows (`window` a multiple of DEEP_SCALE; the
    windows start on deep cells' edges so both feature maps cover the same pixels)."""
    assert data.deep is not None
    features, deep_windows, heatmaps, cells, sides = [], [], [], [], []
    for b, n in enumerate(index):
        starts = rng.integers(0, (CELLS - window) // DEEP_SCALE + 1, size=2) * DEEP_SCALE
        y0, x0 = (int(v) for v in starts)
        heat, centres, box_sides = center_targets(
            data.boxes[n], data.class_index[n], num_classes, CELLS, STRIDE
        )
        features.append(data.features[n, :, y0 : y0 + window, x0 : x0 + window])
        deep_windows.append((y0 // DEEP_SCALE, x0 // DEEP_SCALE))
        heatmaps.append(heat[:, y0 : y0 + window, x0 : x0 + window])
        for (row, col), side in zip(centres, box_sides, strict=True):
            if y0 <= row < y0 + window and x0 <= col < x0 + window:
                cells.append((b, int(row - y0), int(col - x0)))
                sides.append(side)
    target_sides = torch.from_numpy(np.array(sides, np.float32).reshape(-1, 4))
    return Batch(
        features=torch.from_numpy(np.stack(features).astype(np.float32)),
        deep_input=torch.from_numpy(data.deep[index].astype(np.float32)),
        deep_windows=deep_windows,
        heatmaps=torch.from_numpy(np.stack(heatmaps)),
        cells=cells,
        target_sides=target_sides,
    )


def validation_map(
    head: DetectorHead, data: FeatureSet, trained: list[str], classes: list[str], coco_weight: float
) -> tuple[float, DetectionEvaluation]:
    """mAP@0.5 over the trained classes on validation photos (the contract's decoding)."""
    exported = ExportedHead(head, trained, classes, coco_weight).eval()
    coco, deep = data.coco, data.deep
    assert coco is not None and deep is not None
    with torch.no_grad():
        raw_outputs = (
            exported(
                torch.from_numpy(data.features[n : n + 1].astype(np.float32)),
                torch.from_numpy(coco[n : n + 1].astype(np.float32)),
                torch.from_numpy(deep[n : n + 1].astype(np.float32)),
            ).numpy()
            for n in range(len(data.features))
        )
        return score_raw(raw_outputs, data, classes, set(trained))


def optimiser_with_copies(
    net: torch.nn.Module,
    copies: list[torch.nn.Parameter],
    learning_rate: float,
    copy_share: float,
    total_steps: int,
) -> tuple[torch.optim.AdamW, torch.optim.lr_scheduler.OneCycleLR]:
    """AdamW over `net`, with the copied pretrained blocks among its parameters (`copies`, if
    any) at `copy_share` of the rate (they start trained, the rest does not), and one-cycle
    schedules for both."""
    own = {id(p) for p in copies}
    groups = [{"params": [p for p in net.parameters() if id(p) not in own]}]
    rates = [learning_rate]
    if copies:
        groups.append({"params": copies})
        rates.append(learning_rate * copy_share)
    optimiser = torch.optim.AdamW(groups, lr=learning_rate, weight_decay=1e-4)
    schedule = torch.optim.lr_scheduler.OneCycleLR(optimiser, rates, total_steps=total_steps)
    return optimiser, schedule


def train_detector(
    train_photos: Sequence[BoxedPhoto],
    validation_photos: Sequence[BoxedPhoto],
    config: DetectorTrainConfig,
    out_dir: Path,
    progress: TrainProgress | None = None,
) -> dict[str, Any]:
    say = progress or (lambda fraction, line: None)
    started = time.perf_counter()
    torch.manual_seed(config.seed)
    rng = np.random.default_rng(config.seed)
    trained = classes_in(train_photos)
    classes = final_classes(trained)
    learned = [classes.index(c) for c in trained]
    blocks = deep_blocks(config.coco_model) if config.tune_deep_blocks else None
    head = DetectorHead(len(trained), box_head_weights(config.coco_model), config.hidden, blocks)
    extractor = FeatureExtractor(config.coco_model, deep_input=head.deep_input)
    views = [p for p in train_photos for _ in range(config.views)]
    # Of the run's progress, the features take the first quarter, the epochs the rest.
    train = extract(
        views, trained, extractor, rng, False, say, "training photos", config.retexture, (0, 0.2)
    )
    validation = extract(
        validation_photos, trained, extractor, None, True, say, "validation", share=(0.2, 0.25)
    )
    steps = -(-len(views) // config.batch)
    optimiser, schedule = optimiser_with_copies(
        head,
        list(head.deep_blocks.parameters()) if head.deep_blocks is not None else [],
        config.learning_rate,
        config.deep_blocks_learning_rate,
        steps * config.epochs,
    )
    record = EpochRecord(head, started)
    for epoch in range(1, config.epochs + 1):
        head.train()
        total = 0.0
        order = rng.permutation(len(views))
        for start in range(0, len(views), config.batch):
            index = order[start : start + config.batch]
            batch = _batch(train, index, config.window, len(trained), rng)
            logits, sides = head(batch.features, batch.deep_features(head, config.window))
            loss = detection_loss(logits, sides, batch.heatmaps, batch.cells, batch.target_sides)
            optimiser.zero_grad()
            loss.backward()  # type: ignore[no-untyped-call]
            optimiser.step()
            schedule.step()
            total += loss.item() * len(index)
        head.eval()
        score, _ = validation_map(head, validation, trained, classes, 0.0)
        say(0.25 + 0.75 * epoch / config.epochs, record.add(epoch, total / len(views), score))
    record.keep_best()
    rules = {
        weight: validation_map(head, validation, trained, classes, weight)[1].summary(set(trained))
        for weight in (0.0, config.coco_weight)
    }
    out_dir.mkdir(parents=True, exist_ok=True)
    # The head's weights alone, so the COCO rule can be changed without training again.
    torch.save({"state": head.state_dict(), "trained": trained}, out_dir / HEAD_FILE)
    exported = ExportedHead(head, trained, classes, config.coco_weight)
    example = preprocess(validation_photos[0].rgb)
    difference = export_detector(exported, config.coco_model, example, out_dir / MODEL_FILE)
    metrics = {
        "classes": classes,
        "trained_classes": trained,
        "learned_channels": learned,
        "validation_by_rule": {str(w): s for w, s in rules.items()},
        "train_photos": len(train_photos),
        "validation_photos": len(validation_photos),
        "export_difference": difference,
    }
    metadata = {
        "name": model_name(config),
        "label_space": "nyu40",
        "classes": classes,
        "coco_weight": config.coco_weight,
        "provenance": {
            "backbone": "the COCO CenterNet of ../coco_detector (see its metadata.json)",
            "head": "trained by holiscene train-detector on the photos in metrics.json",
        },
    }
    return record.write_files(out_dir, config, metrics, metadata)
