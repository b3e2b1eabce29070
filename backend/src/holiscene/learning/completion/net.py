"""The completion network (PyTorch, training only): a smaller variant of SK-PCN (thesis Ch. 6).

1. Encoder: a PointNet over the partial points (shared MLP, max pool) -> a global code.
2. Meso-skeleton decoder: the code -> K skeleton points.
3. Skeleton-to-surface bridge: every skeleton point, with the code, grows R surface points as
   learned displacements from itself.
4. Surface adjustment: a second PointNet reads the grown points together with the observed
   points (flagged) and predicts a small offset per grown point; the observed points are
   appended to the output unchanged, so what the sensor saw stays in the completed shape.
"""

from __future__ import annotations

from itertools import pairwise

import torch
from torch import nn

from .scans import SKELETON_POINTS

GROWN_PER_SKELETON = 8  # R
CODE = 256


def _mlp(sizes: list[int], last_relu: bool = True) -> nn.Sequential:
    layers: list[nn.Module] = []
    for index, (a, b) in enumerate(pairwise(sizes)):
        layers.append(nn.Linear(a, b))
        if last_relu or index < len(sizes) - 2:
            layers.append(nn.ReLU())
    return nn.Sequential(*layers)


class PointEncoder(nn.Module):
    def __init__(self, inputs: int, code: int) -> None:
        super().__init__()
        self.local = _mlp([inputs, 64, code] if code <= 128 else [inputs, 64, 128, code])

    def forward(self, points: torch.Tensor) -> tuple[torch.Tensor, torch.Tensor]:
        features = self.local(points)  # (B, N, code)
        return features, features.max(dim=1).values


class CompletionNet(nn.Module):
    def __init__(self, skeleton: int = SKELETON_POINTS, grown: int = GROWN_PER_SKELETON) -> None:
        super().__init__()
        self.skeleton, self.grown = skeleton, grown
        self.encoder = PointEncoder(3, CODE)
        self.skeleton_decoder = _mlp([CODE, 512, 512, skeleton * 3], last_relu=False)
        self.bridge = _mlp([CODE + 3, 256, 128, grown * 3], last_relu=False)
        self.adjust_encoder = PointEncoder(4, 128)
        self.adjust = _mlp([128 + 128 + 3, 64, 3], last_relu=False)

    def forward(self, partial: torch.Tensor) -> tuple[torch.Tensor, torch.Tensor, torch.Tensor]:
        """partial (B, N, 3) -> skeleton (B, K, 3), coarse (B, K*R, 3), completed (B, K*R+N, 3)."""
        batch = partial.shape[0]
        _, code = self.encoder(partial)
        skeleton = self.skeleton_decoder(code).view(batch, self.skeleton, 3)
        per_skeleton = torch.cat([skeleton, code[:, None, :].expand(-1, self.skeleton, -1)], dim=2)
        displacement = 0.1 * torch.tanh(self.bridge(per_skeleton))  # grown near its skeleton point
        coarse = skeleton[:, :, None, :] + displacement.view(batch, self.skeleton, self.grown, 3)
        coarse = coarse.reshape(batch, self.skeleton * self.grown, 3)
        flags = torch.cat(
            [
                torch.cat([coarse, torch.zeros_like(coarse[:, :, :1])], dim=2),
                torch.cat([partial, torch.ones_like(partial[:, :, :1])], dim=2),
            ],
            dim=1,
        )
        features, joint = self.adjust_encoder(flags)
        count = coarse.shape[1]
        per_point = torch.cat(
            [
                features[:, :count],
                joint[:, None, :].expand(-1, count, -1),
                coarse,
            ],
            dim=2,
        )
        refined = coarse + 0.05 * torch.tanh(self.adjust(per_point))
        return skeleton, coarse, torch.cat([refined, partial], dim=1)


def _nearest(a: torch.Tensor, b: torch.Tensor) -> torch.Tensor:
    """Index in b of each point of a's nearest neighbour (no gradient: only the pairs matter)."""
    with torch.no_grad():
        distance = b.square().sum(dim=2)[:, None, :] - 2.0 * torch.bmm(a, b.transpose(1, 2))
        return distance.argmin(dim=2)


def _gather(points: torch.Tensor, index: torch.Tensor) -> torch.Tensor:
    return torch.gather(points, 1, index[:, :, None].expand(-1, -1, 3))


def chamfer(a: torch.Tensor, b: torch.Tensor) -> torch.Tensor:
    """Symmetric Chamfer distance (mean squared nearest distance both ways), batch mean.

    Pairs are found without gradient and only their distances are differentiated: the same
    gradient as through the full distance matrix, at a fraction of the cost on a CPU.
    """
    to_b = (a - _gather(b, _nearest(a, b))).square().sum(dim=2).mean()
    to_a = (b - _gather(a, _nearest(b, a))).square().sum(dim=2).mean()
    return to_a + to_b
