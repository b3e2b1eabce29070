"""The default Relation Network: every object's supporter and support type in one pass.

The thesis's network (research/thesis_rn.py) answers one question per forward pass over 100 x 100
feature-cell pairs, which costs about 0.8 s a question on 2 cores. This one reasons over object
pairs instead: each object is a vector of image features pooled under its mask plus its class
and box; each ordered pair adds contact cues measured on the masks (does the child's bottom
edge rest on the other's mask, do the masks touch, does one box hold the other). A pair MLP
scores (supporter, type) for every object and for the floor, walls and ceiling, so a 20-object
scene is one small CNN pass and a few hundred MLP rows.
"""

from __future__ import annotations

import itertools

import torch
import torch.nn.functional as F
from holiscene_schema import NYU40_CLASSES
from holiscene_schema.relation_model import MASK_SIZE, STRUCTURAL_COLUMNS, SUPPORT_TYPE_ORDER
from torch import Tensor, nn

N_TYPES = len(SUPPORT_TYPE_ORDER)
N_STRUCTURAL = len(STRUCTURAL_COLUMNS)
CONTACT_ROWS = 3  # how far below its bottom edge (in 64-grid rows) an object may touch
MASKED = -1.0e4  # logit of impossible answers (an object on itself)
EPS = 1e-6


def _conv(c_in: int, c_out: int, stride: int) -> nn.Sequential:
    return nn.Sequential(
        nn.Conv2d(c_in, c_out, 3, stride=stride, padding=1, bias=False),
        nn.BatchNorm2d(c_out),
        nn.ReLU(inplace=True),
    )


def _mlp(sizes: list[int]) -> nn.Sequential:
    layers: list[nn.Module] = []
    for i, (a, b) in enumerate(itertools.pairwise(sizes)):
        layers.append(nn.Linear(a, b))
        if i < len(sizes) - 2:
            layers.append(nn.ReLU(inplace=True))
    return nn.Sequential(*layers)


def shift_down(masks: Tensor, rows: int) -> Tensor:
    """Masks (N, S, S) moved `rows` rows down, zeros entering at the top."""
    return F.pad(masks[:, : MASK_SIZE - rows, :], (0, 0, rows, 0))


def box_features(boxes: Tensor, masks: Tensor) -> Tensor:
    """Per object: box corners, centre, size, log area and mask fill, (N, 9)."""
    x0, y0, x1, y1 = boxes.unbind(1)
    w = (x1 - x0).clamp(min=EPS)
    h = (y1 - y0).clamp(min=EPS)
    mask_area = masks.mean(dim=(1, 2))
    fill = mask_area / (w * h).clamp(min=EPS)
    return torch.stack(
        [x0, y0, x1, y1, (x0 + x1) / 2, w, h, torch.log(w * h + EPS), fill.clamp(max=2.0)], dim=1
    )


def pair_features(boxes: Tensor, masks: Tensor) -> Tensor:
    """Cues for 'j holds up i', (N, N, 12): row i = child, column j = candidate supporter."""
    n = masks.shape[0]
    flat = masks.reshape(n, -1)
    area = flat.sum(1).clamp(min=EPS)
    # The child's bottom edge: mask cells whose cell below is not in the mask.
    edge = F.relu(masks - F.pad(masks[:, 1:, :], (0, 0, 0, 1)))
    band = torch.zeros_like(masks)
    for rows in range(1, CONTACT_ROWS + 1):
        band = torch.maximum(band, shift_down(edge, rows))
    band_flat = band.reshape(n, -1)
    band_area = band_flat.sum(1).clamp(min=EPS)
    rests_on = band_flat @ flat.T / band_area[:, None]  # share of the bottom edge on j
    grown = F.max_pool2d(masks[:, None], 5, stride=1, padding=2)[:, 0].reshape(n, -1)
    touches = flat @ grown.T / area[:, None]  # share of i within 2 cells of j

    x0, y0, x1, y1 = (c[:, None] for c in boxes.unbind(1))  # child (N, 1)
    px0, py0, px1, py1 = (c[None, :] for c in boxes.unbind(1))  # supporter (1, N)
    w = (x1 - x0).clamp(min=EPS)
    h = (y1 - y0).clamp(min=EPS)
    pw = (px1 - px0).clamp(min=EPS)
    ph = (py1 - py0).clamp(min=EPS)
    overlap_x = (torch.minimum(x1, px1) - torch.maximum(x0, px0)).clamp(min=0)
    overlap_y = (torch.minimum(y1, py1) - torch.maximum(y0, py0)).clamp(min=0)
    return torch.stack(
        [
            rests_on,
            touches,
            overlap_x / w,
            overlap_y / h,
            overlap_x * overlap_y / (w * h),
            ((x0 + x1) - (px0 + px1)) / (2 * pw),
            (y1 - py0) / ph,  # child's bottom against the supporter's top
            (y1 - py1) / ph,  # ... and against its bottom
            torch.log(w / pw),
            torch.log(h / ph),
            y1 - py0,
            y1 - py1,
        ],
        dim=2,
    )


def structural_features(boxes: Tensor, masks: Tensor) -> Tensor:
    """Cues for the floor, walls and ceiling, per object (N, 4): how much of its bottom edge
    rests on no other object, and where its box sits in the image."""
    n = masks.shape[0]
    flat = masks.reshape(n, -1)
    edge = F.relu(masks - F.pad(masks[:, 1:, :], (0, 0, 0, 1)))
    below = shift_down(edge, 1).reshape(n, -1)
    others = (flat.sum(0, keepdim=True) - flat).clamp(0, 1)
    free = (below * (1 - others)).sum(1) / below.sum(1).clamp(min=EPS)
    return torch.stack([free, boxes[:, 3], boxes[:, 1], 1 - boxes[:, 3]], dim=1)


class SupportNet(nn.Module):
    def __init__(self, width: int = 48, hidden: int = 128, class_dim: int = 16) -> None:
        super().__init__()
        self.backbone = nn.Sequential(
            _conv(3, 16, 2),  # 64
            _conv(16, 32, 2),  # 32
            _conv(32, width, 2),  # 16
            _conv(width, width, 1),
        )
        self.class_embedding = nn.Embedding(len(NYU40_CLASSES), class_dim)
        object_in = 2 * width + class_dim + 9  # features under the mask and in the box
        self.object_mlp = _mlp([object_in, hidden, hidden])
        self.pair_mlp = _mlp([2 * hidden + 12, hidden, hidden, N_TYPES])
        self.structural_embedding = nn.Parameter(torch.randn(N_STRUCTURAL, hidden) * 0.1)
        self.structural_mlp = _mlp([2 * hidden + 4, hidden, N_TYPES])

    def forward(self, image: Tensor, masks: Tensor, boxes: Tensor, classes: Tensor) -> Tensor:
        n = masks.shape[0]
        features = self.backbone((image - 0.5) / 0.25)[0]  # (C, 16, 16)
        cells = features.shape[-1]
        small = F.adaptive_avg_pool2d(masks[:, None], cells)[:, 0].reshape(n, -1)  # (N, 256)
        flat_features = features.reshape(features.shape[0], -1)  # (C, 256)
        under_mask = small @ flat_features.T / small.sum(1, keepdim=True).clamp(min=EPS)
        around = self._box_pool(boxes, cells) @ flat_features.T
        objects = self.object_mlp(
            torch.cat(
                [under_mask, around, self.class_embedding(classes), box_features(boxes, masks)], 1
            )
        )  # (N, H)

        hidden = objects.shape[1]
        child = objects[:, None, :].expand(n, n, hidden)
        parent = objects[None, :, :].expand(n, n, hidden)
        pairs = self.pair_mlp(torch.cat([child, parent, pair_features(boxes, masks)], 2))
        self_pair = torch.eye(n, dtype=torch.bool)[:, :, None]
        pairs = pairs.masked_fill(self_pair, MASKED)  # (N, N, T)

        structural_in = torch.cat(
            [
                objects[:, None, :].expand(n, N_STRUCTURAL, hidden),
                self.structural_embedding[None].expand(n, N_STRUCTURAL, hidden),
                structural_features(boxes, masks)[:, None, :].expand(n, N_STRUCTURAL, 4),
            ],
            2,
        )
        return torch.cat([pairs, self.structural_mlp(structural_in)], 1)  # (N, N + 3, T)

    @staticmethod
    def _box_pool(boxes: Tensor, cells: int) -> Tensor:
        """Averaging weights over the feature cells inside each box (N, cells * cells)."""
        centres = (torch.arange(cells, dtype=boxes.dtype) + 0.5) / cells
        inside_x = (centres[None] >= boxes[:, 0:1]) & (centres[None] <= boxes[:, 2:3])
        inside_y = (centres[None] >= boxes[:, 1:2]) & (centres[None] <= boxes[:, 3:4])
        weights = (
            (inside_y[:, :, None] & inside_x[:, None, :])
            .to(boxes.dtype)
            .reshape(boxes.shape[0], -1)
        )
        return weights / weights.sum(1, keepdim=True).clamp(min=1.0)
