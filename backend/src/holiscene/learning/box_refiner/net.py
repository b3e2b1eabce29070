"""The box refiner network (PyTorch, training only): each object's features encoded by an MLP,
then the object relation module (`learning/relation.py`) over the other objects of the
photo, and a head that reads the object with its context. Per target of `features.TARGETS`
it gives the log ratio and the log of how far off that ratio is expected to be (the scale of a
Laplace distribution around it). Trained one photo at a time (a batch of one scene, any number
of objects).

`BoxRefinerEnsemble` averages several such networks trained from different seeds: the mean
of their log ratios is steadier than any one of them, and how much they disagree is a second
measure of doubt.
"""

from __future__ import annotations

from collections.abc import Sequence

import torch
from torch import nn

from ..relation import RelationModule
from .features import PAIR_FEATURES, TARGETS

# The ensemble's output per object: log ratios, log expected errors, members' spread.
OUTPUT_PARTS = ("log_ratio", "log_scale", "spread")
LOG_SCALE_BOUNDS = (-6.0, 3.0)  # a scale of 0.0025 to 20 in log ratio: keeps the loss finite


class BoxRefinerNet(nn.Module):
    def __init__(self, features: int, hidden: int = 128, heads: int = 4) -> None:
        super().__init__()
        self.encode = nn.Sequential(
            nn.Linear(features, hidden), nn.ReLU(), nn.Linear(hidden, hidden), nn.ReLU()
        )
        self.relation = RelationModule(hidden, heads, PAIR_FEATURES)
        self.head = nn.Sequential(
            nn.Linear(2 * hidden, hidden), nn.ReLU(), nn.Linear(hidden, 2 * len(TARGETS))
        )

    def forward(self, objects: torch.Tensor, pairs: torch.Tensor) -> torch.Tensor:
        """objects (1, n, features) normalised, pairs (1, n, n, PAIR_FEATURES) -> (1, n, 8):
        the log ratios, then the log scales (bounded by LOG_SCALE_BOUNDS)."""
        encoded = self.encode(objects)
        context = self.relation(encoded, pairs)
        out: torch.Tensor = self.head(torch.cat([encoded, context], dim=-1))
        targets = len(TARGETS)
        log_scales = out[..., targets:].clamp(*LOG_SCALE_BOUNDS)
        return torch.cat([out[..., :targets], log_scales], dim=-1)


class BoxRefinerEnsemble(nn.Module):
    def __init__(self, members: Sequence[BoxRefinerNet]) -> None:
        super().__init__()
        self.members = nn.ModuleList(members)

    def forward(self, objects: torch.Tensor, pairs: torch.Tensor) -> torch.Tensor:
        """(1, n, 12): per target the members' mean log ratio, the log of their mean scale,
        and the spread (standard deviation) of their log ratios, in OUTPUT_PARTS order."""
        outputs = torch.stack([member(objects, pairs) for member in self.members])
        targets = len(TARGETS)
        ratios = outputs[..., :targets]
        scales = torch.exp(outputs[..., targets:]).mean(0)
        spread = ratios.std(0, correction=0)
        return torch.cat([ratios.mean(0), torch.log(scales), spread], dim=-1)
