"""An NYU-40 class head on PicoDet's anchors (PyTorch), its targets and its export.

PicoDet's boxes stay as they are (`picodet_taps.py`: they already meet almost every real
object); the head only learns which NYU-40 class each anchor's box holds, and how well. Each
level's class branch (five convolutions and a squeeze-and-excite, 43 thousand weights) is
copied from the graph (`onnx_subgraph.py`) and fine-tuned; its 96 class features, the
alignment probability and COCO's 80 scores (COCO's own verdicts are evidence too) then go
through a 1x1 convolution, a depthwise 3x3 (neighbouring anchors), and two more 1x1
convolutions shared by the four levels. PicoDet's own branches, boxes and COCO scores are not
touched.

Targets are fixed before training, because the boxes are: each true box takes the anchors
inside it whose boxes meet it best (as many as the sum of its ten best IoUs, at least one), an
anchor shared by two true boxes goes to the one it meets better, and an anchor's target is its
box's IoU with its true box (GFL's quality focal loss: the score says how good the box is).
"""

from __future__ import annotations

import io
from collections.abc import Sequence
from pathlib import Path

import numpy as np
import onnx
import torch
from holiscene_schema.detector_model import COCO_CLASSES, MAX_DETECTIONS, OUTPUT_NAME
from onnx import helper
from torch import nn

from .net import coco_sources, mapped_coco, own_channels
from .onnx_subgraph import OnnxSubgraph
from .picodet_contract import suffix_nodes, upstream
from .picodet_taps import FEATURE_CHANNELS, STRIDES, NmsSettings, PicoDetTapNames, grid_sizes
from .runtime import box_iou

EVIDENCE_CHANNELS = 1 + len(COCO_CLASSES)  # the alignment probability, COCO's scores
INPUT_CHANNELS = FEATURE_CHANNELS + EVIDENCE_CHANNELS
CANDIDATE_IOUS = 10  # a true box's anchors: as many as the sum of its best ten IoUs
HEAD_PREFIX = "nyu_head/"
HEAD_SCORES = HEAD_PREFIX + "scores"


def anchor_targets(
    anchor_boxes: np.ndarray, points: np.ndarray, truth: np.ndarray, truth_class: np.ndarray
) -> tuple[np.ndarray, np.ndarray]:
    """Each anchor's class (-1: background) and IoU target, for true boxes [M, 4] of classes
    [M] against anchor boxes [N, 4] centred on `points` [N, 2] (the same pixels)."""
    count = len(anchor_boxes)
    target_class = np.full(count, -1, np.int16)
    target_iou = np.zeros(count, np.float32)
    if len(truth) == 0:
        return target_class, target_iou
    iou = np.stack([box_iou(box, anchor_boxes) for box in truth])  # [M, N]
    inside = (
        (points[None, :, 0] >= truth[:, None, 0])
        & (points[None, :, 0] <= truth[:, None, 2])
        & (points[None, :, 1] >= truth[:, None, 1])
        & (points[None, :, 1] <= truth[:, None, 3])
    )
    candidate_iou = np.where(inside, iou, 0.0)
    for m in range(len(truth)):
        order = np.argsort(-candidate_iou[m])
        k = max(1, int(candidate_iou[m, order[:CANDIDATE_IOUS]].sum()))
        chosen = [n for n in order[:k] if candidate_iou[m, n] > 0]
        for n in chosen:
            if candidate_iou[m, n] > target_iou[n]:
                target_iou[n] = candidate_iou[m, n]
                target_class[n] = truth_class[m]
    return target_class, target_iou


def quality_focal_loss(
    logits: torch.Tensor, target_class: torch.Tensor, target_iou: torch.Tensor
) -> torch.Tensor:
    """GFL's quality focal loss over [B, N, K] logits, per positive anchor."""
    target = torch.zeros_like(logits)
    positive = target_class >= 0
    b, n = torch.nonzero(positive, as_tuple=True)
    target[b, n, target_class[b, n].long()] = target_iou[b, n]
    probability = torch.sigmoid(logits)
    loss = nn.functional.binary_cross_entropy_with_logits(logits, target, reduction="none")
    loss = loss * (probability - target).abs().pow(2)
    return loss.sum() / positive.sum().clamp(min=1)


def class_branches(model: onnx.ModelProto, names: PicoDetTapNames) -> nn.ModuleList:
    """Trainable copies of PicoDet's four class branches (branch input -> class features)."""
    return nn.ModuleList(
        OnnxSubgraph(model, start, end)
        for start, end in zip(names.branch_inputs, names.features, strict=True)
    )


def flatten_levels(levels: list[torch.Tensor]) -> torch.Tensor:
    """Per-level maps [B, C, H, W] -> [B, C, N], anchors in the graph's order."""
    return torch.cat([level.flatten(2) for level in levels], dim=2)


class PicoDetClassHead(nn.Module):
    """Per-anchor branch inputs [B, 96, N] and evidence [B, N, EVIDENCE_CHANNELS] (alignment,
    COCO's scores) -> [B, N, K] class logits, through the copies of PicoDet's class branches.
    The 1x1 convolutions after them are linear layers over the anchors (several times
    faster on the CPU)."""

    def __init__(self, classes: int, branches: nn.ModuleList, hidden: int = 96) -> None:
        super().__init__()
        self.branches = branches
        self.reduce = nn.Sequential(nn.Linear(INPUT_CHANNELS, hidden), nn.Hardswish())
        self.neighbours = nn.Sequential(
            nn.Conv2d(hidden, hidden, 3, padding=1, groups=hidden), nn.Hardswish()
        )
        self.mix = nn.Sequential(nn.Linear(hidden, hidden), nn.Hardswish())
        self.out = nn.Linear(hidden, classes)
        nn.init.constant_(self.out.bias, -4.6)  # a prior of 1% per class and anchor

    def _levels(self, flat: torch.Tensor) -> list[torch.Tensor]:
        levels, start = [], 0
        for cells in grid_sizes():
            level = flat[:, :, start : start + cells * cells]
            levels.append(level.reshape(flat.shape[0], flat.shape[1], cells, cells))
            start += cells * cells
        return levels

    def forward(self, branch_inputs: torch.Tensor, evidence: torch.Tensor) -> torch.Tensor:
        features = [
            branch(level)
            for branch, level in zip(self.branches, self._levels(branch_inputs), strict=True)
        ]
        anchors = torch.cat([flatten_levels(features).transpose(1, 2), evidence], dim=2)
        hidden = self.reduce(anchors)
        around = [
            self.neighbours(level).flatten(2).transpose(1, 2)
            for level in self._levels(hidden.transpose(1, 2))
        ]
        logits: torch.Tensor = self.out(self.mix(hidden + torch.cat(around, dim=1)))
        return logits


class ScoringHead(nn.Module):
    """The exported scoring: the head's inputs -> [B, K, N] scores in the model's class list:
    the head's sigmoid for the classes it learned, COCO's mapped scores for the classes only
    COCO knows, and the larger of the head's and `coco_weight` times COCO's where both do.
    The head's own score of an `unnamed` class is left out (COCO's evidence for it stays):
    a class it learned but names wrongly on real photos."""

    def __init__(
        self,
        head: PicoDetClassHead,
        trained: list[str],
        classes: list[str],
        coco_weight: float,
        unnamed: Sequence[str] = (),
    ) -> None:
        super().__init__()
        self.head = head
        index, mask = coco_sources(classes)
        named = [c for c in trained if c not in unnamed]
        learned = np.array([c in named for c in classes])
        weight = mask * np.where(learned, coco_weight, 1.0).astype(np.float32)
        self.own_channel: torch.Tensor
        self.coco_index: torch.Tensor
        self.coco_weight: torch.Tensor
        own = own_channels(trained, classes)
        own[[c in unnamed for c in classes]] = len(trained)  # the zero channel
        self.register_buffer("own_channel", own)
        self.register_buffer("coco_index", torch.from_numpy(index))
        self.register_buffer("coco_weight", torch.from_numpy(weight))

    def forward(self, branch_inputs: torch.Tensor, evidence: torch.Tensor) -> torch.Tensor:
        probability = torch.sigmoid(self.head(branch_inputs, evidence)).transpose(1, 2)
        zero = torch.zeros_like(probability[:, :1])
        ours = torch.cat([probability, zero], dim=1)[:, self.own_channel]
        coco = mapped_coco(evidence[:, :, 1:].transpose(1, 2), self.coco_index)
        return torch.maximum(ours, coco * self.coco_weight.view(1, -1, 1))


class _TapsToScores(nn.Module):
    def __init__(self, scoring: ScoringHead) -> None:
        super().__init__()
        self.scoring = scoring

    def forward(self, *taps: torch.Tensor) -> torch.Tensor:
        levels = len(STRIDES)
        branch_inputs = flatten_levels(list(taps[:levels]))
        alignment = flatten_levels(list(taps[levels : 2 * levels]))
        evidence = torch.cat([alignment, taps[2 * levels]], dim=1).transpose(1, 2)
        scores: torch.Tensor = self.scoring(branch_inputs, evidence)
        return scores


def export_picodet_head(
    scoring: ScoringHead, picodet: onnx.ModelProto, names: PicoDetTapNames, path: Path
) -> onnx.ModelProto:
    """One ONNX file of the detector contract: the wrapped PicoDet up to its taps, the head's
    scores in place of COCO's, then PicoDet's NMS and the contract's rows."""
    tap_inputs = [*names.branch_inputs, *names.alignment, names.coco_scores]
    sizes = grid_sizes()
    anchors = sum(c * c for c in sizes)
    example = (
        *(torch.zeros(1, FEATURE_CHANNELS, c, c) for c in sizes),
        *(torch.zeros(1, 1, c, c) for c in sizes),
        torch.zeros(1, len(COCO_CLASSES), anchors),
    )
    buffer = io.BytesIO()
    torch.onnx.export(
        _TapsToScores(scoring).eval(),
        example,
        buffer,  # type: ignore[arg-type]  # a file-like object is accepted too
        input_names=[HEAD_PREFIX + n for n in tap_inputs],
        output_names=[HEAD_SCORES],
        opset_version=17,
        dynamo=False,
    )
    head_graph = onnx.load_from_string(buffer.getvalue()).graph
    # The head's tensors get the prefix; its inputs become the taps themselves.
    rename = {HEAD_PREFIX + n: n for n in tap_inputs}

    def renamed(name: str) -> str:
        if not name:
            return name
        if name in rename:
            return rename[name]
        return name if name.startswith(HEAD_PREFIX) else HEAD_PREFIX + name

    for node in head_graph.node:
        node.name = renamed(node.name or node.output[0])
        node.input[:] = [renamed(n) for n in node.input]
        node.output[:] = [renamed(n) for n in node.output]
    for tensor in head_graph.initializer:
        tensor.name = renamed(tensor.name)
    graph = picodet.graph
    settings = list(names.nms_settings)
    body = upstream(graph, {*tap_inputs, names.boxes, *settings})
    used = {name for node in body for name in node.input}
    suffix, suffix_constants = suffix_nodes([names.boxes, HEAD_SCORES, *settings])
    merged = helper.make_graph(
        [*body, *head_graph.node, *suffix],
        "picodet_nyu40_detector_contract",
        list(graph.input),
        [
            helper.make_tensor_value_info(
                OUTPUT_NAME, onnx.TensorProto.FLOAT, [1, MAX_DETECTIONS, 6]
            )
        ],
        initializer=[
            *(t for t in graph.initializer if t.name in used),
            *head_graph.initializer,
            *suffix_constants,
        ],
    )
    model = helper.make_model(merged, opset_imports=picodet.opset_import, producer_name="holiscene")
    model.ir_version = picodet.ir_version
    onnx.checker.check_model(model, full_check=True)
    onnx.save(model, str(path))
    return model


def nms_rows(boxes: np.ndarray, scores: np.ndarray, nms: NmsSettings) -> np.ndarray:
    """What the exported tail makes of boxes [N, 4] and scores [K, N]: PicoDet's NMS per
    class, then the contract's MAX_DETECTIONS best rows [k, 6] (for validation in training)."""
    rows: list[tuple[float, ...]] = []
    for k, class_scores in enumerate(scores):
        order = np.argsort(-class_scores, kind="stable")
        order = order[class_scores[order] > nms.lowest_score][: nms.per_class]
        kept: list[int] = []
        for n in order:
            if kept and box_iou(boxes[n], boxes[kept]).max() > nms.iou:
                continue
            kept.append(int(n))
        rows.extend((*map(float, boxes[n]), float(class_scores[n]), float(k)) for n in kept)
    rows.sort(key=lambda r: -r[4])
    out = np.zeros((MAX_DETECTIONS, 6), np.float32)
    if rows:
        out[: min(len(rows), MAX_DETECTIONS)] = np.array(rows[:MAX_DETECTIONS], np.float32)
    return out[None]
