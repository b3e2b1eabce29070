"""The NYU-40 detector head (PyTorch, training only) on the COCO detector's frozen features,
its decoding, and the export of backbone + head as one ONNX file of the detector contract.

Head: the neck's features through a 1x1 and a 3x3 convolution, the backbone's deep features
(before the neck squeezed them for COCO's classes) through a 1x1 and a 3x3 convolution and
scaled up to the neck's grid, both joined by a 1x1 convolution to one heatmap per class
(CenterNet; ReLUs between), and the COCO model's own box head (left, top, right, bottom
distances from each cell), its last layer fine-tuned. Reading the deep features raised the
validation mAP@0.5 from 27.3 to 34.7 at the same training (docs/detector.md). With
`deep_blocks` the head reads instead its own copy of the backbone's stride-32 blocks, fed
by the backbone's features at a 16th of the input and fine-tuned with it; the backbone, its
neck and COCO's heads stay as they were.
For the classes COCO knows, the COCO heatmap can join by a rule (`coco_weight`): each
class's score is the larger of the new head's and `coco_weight` times COCO's (0: the new
head alone).
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
import onnx
import torch
import torch.nn.functional as F
from holiscene_schema.detector_model import (
    COCO_TO_NYU40,
    INPUT_NAME,
    MAX_DETECTIONS,
    OPSET,
    OUTPUT_NAME,
)
from torch import nn

from ..export import keep_if_faithful
from .backbone import (
    DEEP_CHANNELS,
    DEEP_FEATURES,
    FEATURE_CHANNELS,
    FEATURES,
    MID_FEATURES,
    BoxHeadWeights,
    backbone_model,
)
from .onnx_subgraph import OnnxSubgraph
from .row_matching import rows_difference

STRIDE = 4
# Rows of PyTorch and onnxruntime matched as row_matching says (near-ties may swap): box
# corners as shares of the 512-pixel input (0.05 px), scores in their own units.
EXPORT_TOLERANCE = 1e-4


def deep_blocks(coco_model: Path) -> OnnxSubgraph:
    """A trainable copy of the COCO backbone's stride-32 blocks: features at a 16th of the
    input -> the deep features."""
    return OnnxSubgraph(onnx.load(str(coco_model)), MID_FEATURES, DEEP_FEATURES)


class DetectorHead(nn.Module):
    def __init__(
        self,
        num_classes: int,
        box: BoxHeadWeights,
        hidden: int = 64,
        deep_blocks: nn.Module | None = None,
    ) -> None:
        super().__init__()
        self.deep_blocks = deep_blocks
        # Full 3x3 convolutions on few channels: PyTorch's depthwise backward is several
        # times slower on CPU than this.
        self.local = nn.Sequential(
            nn.Conv2d(FEATURE_CHANNELS, hidden, 1),
            nn.ReLU(inplace=True),
            nn.Conv2d(hidden, hidden, 3, padding=1),
            nn.ReLU(inplace=True),
        )
        self.deep = nn.Sequential(
            nn.Conv2d(DEEP_CHANNELS, hidden, 1),
            nn.ReLU(inplace=True),
            nn.Conv2d(hidden, hidden, 3, padding=1),
            nn.ReLU(inplace=True),
        )
        self.joined = nn.Sequential(
            nn.Conv2d(2 * hidden, hidden, 1),
            nn.ReLU(inplace=True),
            nn.Conv2d(hidden, num_classes, 1),
        )
        last = self.joined[-1]
        assert isinstance(last, nn.Conv2d) and last.bias is not None
        nn.init.constant_(last.bias, -2.19)  # a prior of 0.1 per cell, as CenterNet starts
        # The COCO box head: its depthwise part stays as trained, its last layer is tuned.
        self.box_depthwise = nn.Conv2d(
            FEATURE_CHANNELS, FEATURE_CHANNELS, 3, padding=1, groups=FEATURE_CHANNELS, bias=False
        )
        self.box_pointwise = nn.Conv2d(FEATURE_CHANNELS, 4, 1)
        with torch.no_grad():
            self.box_depthwise.weight.copy_(torch.from_numpy(box.depthwise.copy()))
            self.box_pointwise.weight.copy_(torch.from_numpy(box.pointwise.copy()))
            assert self.box_pointwise.bias is not None
            self.box_pointwise.bias.copy_(torch.from_numpy(box.bias.copy()))
        self.box_depthwise.requires_grad_(False)
        self.box_scale = box.scale

    @property
    def deep_input(self) -> str:
        """The backbone tensor the deep branch reads."""
        return DEEP_FEATURES if self.deep_blocks is None else MID_FEATURES

    def deep_features(self, deep_input: torch.Tensor) -> torch.Tensor:
        """The deep features [B, 480, S / 32, S / 32] from the backbone tensor `deep_input`
        names (whole photos: the blocks' squeeze-and-excite pools over all of it)."""
        return deep_input if self.deep_blocks is None else self.deep_blocks(deep_input)

    def forward(
        self, features: torch.Tensor, deep: torch.Tensor
    ) -> tuple[torch.Tensor, torch.Tensor]:
        """(class logits [B, K, H, W], box sides [B, 4, H, W] in input pixels) from the neck's
        features [B, 128, H, W] and the deep ones [B, 480, H / 8, W / 8]."""
        sides = self.box_pointwise(self.box_depthwise(features)) * self.box_scale
        local = self.local(features)
        deep_up = F.interpolate(
            self.deep(deep), size=local.shape[-2:], mode="bilinear", align_corners=False
        )
        return self.joined(torch.cat([local, deep_up], dim=1)), sides


def coco_sources(classes: list[str]) -> tuple[np.ndarray, np.ndarray]:
    """For each class, up to three COCO channels that map to it (index array [K, 3]) and
    whether it has any (mask [K])."""
    sources = [[i for i, nyu in enumerate(COCO_TO_NYU40) if nyu == cls] for cls in classes]
    width = max(3, max((len(s) for s in sources), default=0))
    index = np.array([(s or [0]) + [(s or [0])[0]] * (width - len(s or [0])) for s in sources])
    mask = np.array([1.0 if s else 0.0 for s in sources], dtype=np.float32)
    return index.astype(np.int64), mask


def own_channels(trained: list[str], classes: list[str]) -> torch.Tensor:
    """Each class's channel of a head that learned `trained`, or the zero channel after the
    last one (to be appended) for a class it did not learn."""
    own = [trained.index(c) if c in trained else len(trained) for c in classes]
    return torch.tensor(own, dtype=torch.int64)


def mapped_coco(coco: torch.Tensor, index: torch.Tensor) -> torch.Tensor:
    """Each class's COCO evidence: the largest of its COCO channels (`coco_sources`' index
    [K, S]) of COCO's scores [B, 80, ...], class-wise on dimension 1."""
    mapped = coco[:, index[:, 0]]
    for j in range(1, index.shape[1]):
        mapped = torch.maximum(mapped, coco[:, index[:, j]])
    return mapped


class ExportedHead(nn.Module):
    """Features, the COCO heatmap and the deep branch's input (NCHW) -> the contract's raw
    detections."""

    def __init__(
        self, head: DetectorHead, trained: list[str], classes: list[str], coco_weight: float
    ) -> None:
        super().__init__()
        self.head = head
        index, mask = coco_sources(classes)
        self.own_channel: torch.Tensor
        self.coco_index: torch.Tensor
        self.coco_weight: torch.Tensor
        self.register_buffer("own_channel", own_channels(trained, classes))
        self.register_buffer("coco_index", torch.from_numpy(index))
        self.register_buffer("coco_weight", torch.from_numpy(mask) * coco_weight)

    def forward(
        self, features: torch.Tensor, coco_heatmap: torch.Tensor, deep_input: torch.Tensor
    ) -> torch.Tensor:
        logits, sides = self.head(features, self.head.deep_features(deep_input))
        zero = torch.zeros_like(logits[:, :1])
        ours = torch.cat([torch.sigmoid(logits), zero], dim=1)[:, self.own_channel]
        coco = mapped_coco(coco_heatmap, self.coco_index)
        heat = torch.maximum(ours, coco * self.coco_weight.view(1, -1, 1, 1))
        return centernet_decode(heat, sides, STRIDE, MAX_DETECTIONS)


def centernet_decode(
    heatmap: torch.Tensor, sides: torch.Tensor, stride: int, top_k: int
) -> torch.Tensor:
    """Raw detections [1, top_k, 6] from class probabilities [1, C, H, W] and box sides
    [1, 4, H, W]: 3x3 peaks, the best top_k over (y, x, class) as the COCO model orders them,
    boxes about each peak's cell."""
    classes, width = heatmap.shape[1], heatmap.shape[3]
    peaks = heatmap * (F.max_pool2d(heatmap, 3, stride=1, padding=1) == heatmap).float()
    scores, index = torch.topk(peaks.permute(0, 2, 3, 1).reshape(1, -1), top_k, dim=1)
    cls = index % classes
    cell = torch.div(index, classes, rounding_mode="floor")
    cx = ((cell % width) * stride).float()[0]
    cy = (torch.div(cell, width, rounding_mode="floor") * stride).float()[0]
    box_sides = sides.permute(0, 2, 3, 1).reshape(-1, 4)[cell[0]]
    boxes = torch.stack(
        [
            cx - box_sides[:, 0],
            cy - box_sides[:, 1],
            cx + box_sides[:, 2],
            cy + box_sides[:, 3],
        ],
        dim=1,
    )
    return torch.cat([boxes, scores[0, :, None], cls[0, :, None].float()], dim=1)[None]


def export_detector(
    exported_head: ExportedHead, coco_model: Path, example: np.ndarray, path: Path
) -> float:
    """Backbone (from the COCO model) and head as one ONNX file at `path`, checked against
    onnxruntime's backbone + PyTorch's head on `example` (an input tensor [1, S, S, 3]);
    returns the largest difference."""
    from .backbone import FeatureExtractor

    exported_head = exported_head.eval()
    deep_input = exported_head.head.deep_input
    features, coco, deep = FeatureExtractor(coco_model, deep_input=deep_input)(example)
    args = (torch.from_numpy(features), torch.from_numpy(coco), torch.from_numpy(deep))
    head_file = path.with_suffix(".head.onnx")
    torch.onnx.export(
        exported_head,
        args,
        str(head_file),
        input_names=["features", "coco_heatmap", "deep_features"],
        output_names=[OUTPUT_NAME],
        opset_version=OPSET,
        dynamo=False,
    )
    head = onnx.load(str(head_file))
    head_file.unlink()
    backbone = backbone_model(coco_model, deep_input)
    merged = onnx.compose.merge_models(
        backbone,
        head,
        io_map=[
            (FEATURES, "features"),
            (backbone.graph.output[1].name, "coco_heatmap"),
            (deep_input, "deep_features"),
        ],
    )
    merged.doc_string = "NYU-40 detector: COCO CenterNet backbone, head fine-tuned by HoliScene"
    tmp = path.with_suffix(".tmp.onnx")
    onnx.save(merged, str(tmp))
    with torch.no_grad():
        expected = exported_head(*args).numpy()
    return keep_detector_if_faithful(tmp, path, example, expected)


def keep_detector_if_faithful(
    exported: Path, path: Path, example: np.ndarray, expected: np.ndarray
) -> float:
    """keep_if_faithful for a detector of the contract: its rows on `example` (an input
    [1, S, S, 3]) against PyTorch's `expected`, near-ties allowed to swap."""
    return keep_if_faithful(
        exported,
        path,
        {INPUT_NAME: example},
        OUTPUT_NAME,
        expected,
        EXPORT_TOLERANCE,
        rows_difference(EXPORT_TOLERANCE),
    )
