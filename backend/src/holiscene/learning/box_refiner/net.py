"""The box refiner network (PyTorch, training only): each object's features encoded by an MLP,
then the object relation module (Total3DUnderstanding, after Hu et al. 2018): multi-head
attention over the other objects of the photo whose weights also depend on the pair's 2D box
geometry, and a head that reads the object with its context and gives the log ratios of
`features.TARGETS`. Trained one photo at a time (a batch of one scene, any number of objects).
"""

from __future__ import annotations

import math

import torch
from torch import nn

from .features import PAIR_FEATURES, TARGETS


class BoxRefinerNet(nn.Module):
    def __init__(self, features: int, hidden: int = 128, heads: int = 4) -> None:
        super().__init__()
        self.heads = heads
        self.scale = 1.0 / math.sqrt(hidden // heads)  # of the attention's dot products
        self.encode = nn.Sequential(
            nn.Linear(features, hidden), nn.ReLU(), nn.Linear(hidden, hidden), nn.ReLU()
        )
        self.query = nn.Linear(hidden, hidden)
        self.key = nn.Linear(hidden, hidden)
        self.value = nn.Linear(hidden, hidden)
        self.geometry = nn.Sequential(nn.Linear(PAIR_FEATURES, 32), nn.ReLU(), nn.Linear(32, heads))
        self.head = nn.Sequential(
            nn.Linear(2 * hidden, hidden), nn.ReLU(), nn.Linear(hidden, len(TARGETS))
        )

    def forward(self, objects: torch.Tensor, pairs: torch.Tensor) -> torch.Tensor:
        """objects (1, n, features) normalised, pairs (1, n, n, PAIR_FEATURES) -> (1, n, 4)."""
        encoded = self.encode(objects)
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
        context = (weights @ value).transpose(1, 2).reshape(batch, n, hidden)
        out: torch.Tensor = self.head(torch.cat([encoded, context], dim=-1))
        return out
