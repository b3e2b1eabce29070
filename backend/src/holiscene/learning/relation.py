"""The object relation module (Total3DUnderstanding, after Hu et al. 2018), PyTorch, training
only: multi-head attention over the other objects of one photo whose weights are the
appearance term (query against key) plus the log of a learned geometric weight from the pair's
2D box geometry (`box_refiner.features.pair_features`). The box refiner and the object
detection network (`scene_net`) both read their objects through it."""

from __future__ import annotations

import math

import torch
from torch import nn


class RelationModule(nn.Module):
    def __init__(self, hidden: int, heads: int, pair_features: int) -> None:
        super().__init__()
        self.heads = heads
        self.scale = 1.0 / math.sqrt(hidden // heads)  # of the attention's dot products
        self.query = nn.Linear(hidden, hidden)
        self.key = nn.Linear(hidden, hidden)
        self.value = nn.Linear(hidden, hidden)
        self.geometry = nn.Sequential(nn.Linear(pair_features, 32), nn.ReLU(), nn.Linear(32, heads))

    def forward(self, encoded: torch.Tensor, pairs: torch.Tensor) -> torch.Tensor:
        """encoded (batch, n, hidden), pairs (batch, n, n, pair_features) -> each object's
        context (batch, n, hidden)."""
        batch, n, hidden = encoded.shape
        width = hidden // self.heads

        def split(layer: nn.Linear) -> torch.Tensor:
            heads: torch.Tensor = layer(encoded).reshape(batch, n, self.heads, width)
            return heads.transpose(1, 2)

        query, key, value = split(self.query), split(self.key), split(self.value)
        appearance = query @ key.transpose(2, 3) * self.scale
        # Geometric weight: a pair the geometry rules out gets (almost) no attention.
        geometric = self.geometry(pairs).permute(0, 3, 1, 2)
        weights = torch.softmax(appearance + torch.log(torch.relu(geometric) + 1e-6), dim=-1)
        context: torch.Tensor = (weights @ value).transpose(1, 2).reshape(batch, n, hidden)
        return context
