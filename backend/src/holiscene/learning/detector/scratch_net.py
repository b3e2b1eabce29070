"""A small CenterNet trained from scratch on synthetic rooms (PyTorch, training only), and its
export as one ONNX file of the detector contract, checked against PyTorch.

No pretrained weight anywhere: the point is to measure what synthetic rooms alone teach, beside
the COCO model and the NYU-40 head fine-tuned over COCO's backbone. To train on two CPU cores
the graph first halves the contract's 512-pixel input (a 2x2 mean, which is what bilinear
resampling with half-pixel centres gives for a factor of 2), so the net sees 256 x 256:

- a trunk of plain 3x3 convolutions with batch norm (PyTorch's depthwise backward is slow on
  CPU), four stride-2 steps with a residual block each, down to 8 x 8 cells;
- a top-down neck (nearest upsampling plus 1x1 lateral convolutions) back to 64 x 64 cells, one
  cell per 8 input pixels;
- from the neck's last 3x3 convolution, one heatmap per class and the box's four sides (left,
  top, right, bottom from the cell, input pixels, positive by an exponential);
- the COCO model's decoding (net.centernet_decode): 3x3 peaks, the best 100.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
import torch
import torch.nn.functional as F
from holiscene_schema.detector_model import (
    INPUT_NAME,
    INPUT_SIZE,
    MAX_DETECTIONS,
    OPSET,
    OUTPUT_NAME,
)
from torch import nn

from .net import centernet_decode, keep_detector_if_faithful

NET_SIZE = INPUT_SIZE // 2  # what the net sees after the graph's 2x2 mean
STRIDE = 8  # input pixels per heatmap cell
CELLS = INPUT_SIZE // STRIDE
WIDTHS = (16, 32, 64, 96, 128)  # channels at 1/2, 1/4, 1/8, 1/16, 1/32 of NET_SIZE
NECK = 48
SIDE_SCALE = 16.0  # input pixels of a box side when the side's output is 0


def halve(images: np.ndarray) -> np.ndarray:
    """Contract input [1, S, S, 3] -> the net's input [1, 3, S/2, S/2] (2x2 means), as the
    graph computes it; training stores this once per photo."""
    size = images.shape[1] // 2
    pooled = images[0].reshape(size, 2, size, 2, 3).mean(axis=(1, 3), dtype=np.float32)
    out: np.ndarray = pooled.transpose(2, 0, 1)[None]
    return out


def _conv(cin: int, cout: int, stride: int = 1) -> nn.Sequential:
    return nn.Sequential(
        nn.Conv2d(cin, cout, 3, stride=stride, padding=1, bias=False),
        nn.BatchNorm2d(cout),
        nn.ReLU(inplace=True),
    )


class Residual(nn.Module):
    def __init__(self, channels: int) -> None:
        super().__init__()
        self.body = nn.Sequential(
            nn.Conv2d(channels, channels, 3, padding=1, bias=False),
            nn.BatchNorm2d(channels),
            nn.ReLU(inplace=True),
            nn.Conv2d(channels, channels, 3, padding=1, bias=False),
            nn.BatchNorm2d(channels),
        )

    def forward(self, x: torch.Tensor) -> torch.Tensor:
        return F.relu(x + self.body(x))


class ScratchNet(nn.Module):
    """The net's input [B, 3, NET_SIZE, NET_SIZE] (RGB 0-255) -> (class logits [B, K, CELLS,
    CELLS], box sides [B, 4, CELLS, CELLS] in contract input pixels)."""

    def __init__(self, num_classes: int) -> None:
        super().__init__()
        w = WIDTHS
        self.stem = nn.Sequential(_conv(3, w[0], 2), _conv(w[0], w[1], 2))
        self.down = nn.ModuleList(
            nn.Sequential(_conv(w[i], w[i + 1], 2), Residual(w[i + 1])) for i in (1, 2, 3)
        )
        self.lateral = nn.ModuleList(nn.Conv2d(w[i], NECK, 1) for i in (4, 3, 2, 1))
        self.smooth = nn.ModuleList(_conv(NECK, NECK) for _ in range(3))
        self.classes = nn.Conv2d(NECK, num_classes, 1)
        self.sides = nn.Conv2d(NECK, 4, 1)
        assert self.classes.bias is not None
        nn.init.constant_(self.classes.bias, -2.19)  # a prior of 0.1 per cell, as CenterNet starts

    def forward(self, x: torch.Tensor) -> tuple[torch.Tensor, torch.Tensor]:
        levels = [self.stem((x - 127.5) / 64.0)]
        for block in self.down:
            levels.append(block(levels[-1]))
        top = self.lateral[0](levels[-1])
        for lateral, smooth, level in zip(
            self.lateral[1:], self.smooth, reversed(levels[:-1]), strict=True
        ):
            top = smooth(F.interpolate(top, scale_factor=2.0, mode="nearest") + lateral(level))
        sides = torch.exp(self.sides(top).clamp(-4.0, 4.0)) * SIDE_SCALE
        return self.classes(top), sides


class ScratchDetector(nn.Module):
    """The contract's input [1, S, S, 3] -> its raw detections [1, MAX_DETECTIONS, 6]."""

    def __init__(self, net: ScratchNet) -> None:
        super().__init__()
        self.net = net

    def forward(self, images: torch.Tensor) -> torch.Tensor:
        return self.decode(*self.net(F.avg_pool2d(images.permute(0, 3, 1, 2), 2)))

    def decode(self, logits: torch.Tensor, sides: torch.Tensor) -> torch.Tensor:
        return centernet_decode(torch.sigmoid(logits), sides, STRIDE, MAX_DETECTIONS)


def export_scratch_detector(net: ScratchNet, example: np.ndarray, path: Path) -> float:
    """The detector as one ONNX file at `path`, checked against PyTorch on `example` (an input
    tensor [1, S, S, 3]); returns the largest difference (raises if above the tolerance)."""
    detector = ScratchDetector(net).eval()
    args = (torch.from_numpy(example),)
    tmp = path.with_suffix(".tmp.onnx")
    torch.onnx.export(
        detector,
        args,
        str(tmp),
        input_names=[INPUT_NAME],
        output_names=[OUTPUT_NAME],
        opset_version=OPSET,
        dynamo=False,
    )
    with torch.no_grad():
        expected = detector(*args).numpy()
    return keep_detector_if_faithful(tmp, path, example, expected)
