"""The mesh network (PyTorch; training only): a silhouette encoder, and a decoder that moves
each template vertex and predicts how far from the true surface it will still be.

The decoder is one MLP shared by all vertices, fed the vertex's position and the object's
code (as Total3DUnderstanding's MGN and AtlasNet), so it serves templates of any vertex count.
Its first layer is split into a vertex part and a code part, so the code's share is computed
once per object rather than once per vertex.
"""

from __future__ import annotations

from itertools import pairwise

import torch
from torch import nn

from .inputs import CONDITION_SIZE, SILHOUETTE_PIXELS, VERTEX_FEATURES

CODE_SIZE = 256
HIDDEN = 192
# Sines and cosines of the vertex features at these frequencies (times pi): a plain MLP on
# coordinates learns only smooth fields, and neighbouring parts often move apart.
FREQUENCIES = (1.0, 2.0, 4.0)
ENCODED = VERTEX_FEATURES * (1 + 2 * len(FREQUENCIES))


class MeshNet(nn.Module):
    def __init__(self) -> None:
        super().__init__()
        channels = (1, 16, 32, 64, 96)
        layers: list[nn.Module] = []
        for cin, cout in pairwise(channels):
            layers += [nn.Conv2d(cin, cout, 3, stride=2, padding=1), nn.ReLU()]
        self.encoder = nn.Sequential(*layers, nn.Flatten())
        cells = (SILHOUETTE_PIXELS // 16) ** 2 * channels[-1]
        self.code = nn.Sequential(
            nn.Linear(cells + CONDITION_SIZE, CODE_SIZE),
            nn.ReLU(),
            nn.Linear(CODE_SIZE, CODE_SIZE),
            nn.ReLU(),
        )
        self.from_vertex = nn.Linear(ENCODED, HIDDEN)
        self.from_code = nn.Linear(CODE_SIZE, HIDDEN, bias=False)
        self.decoder = nn.Sequential(
            nn.ReLU(),
            nn.Linear(HIDDEN, HIDDEN),
            nn.ReLU(),
            nn.Linear(HIDDEN, HIDDEN),
            nn.ReLU(),
            nn.Linear(HIDDEN, 4),
        )
        last = self.decoder[-1]
        assert isinstance(last, nn.Linear)
        nn.init.zeros_(last.weight)  # start from the template itself
        nn.init.zeros_(last.bias)

    def forward(
        self, silhouette: torch.Tensor, condition: torch.Tensor, template: torch.Tensor
    ) -> tuple[torch.Tensor, torch.Tensor]:
        """silhouette (B, S, S), condition (B, C), template (B, V, VERTEX_FEATURES) ->
        moved vertices (B, V, 3) and their expected distance to the truth (B, V)."""
        image = self.encoder(silhouette[:, None])
        code = self.code(torch.cat([image, condition], dim=1))
        angles = torch.cat([template * (f * torch.pi) for f in FREQUENCIES], dim=2)
        encoded = torch.cat([template, torch.sin(angles), torch.cos(angles)], dim=2)
        hidden = self.from_vertex(encoded) + self.from_code(code)[:, None, :]
        out = self.decoder(hidden)
        moved = template[..., :3] + out[..., :3]
        error = nn.functional.softplus(out[..., 3])
        return moved, error


def chamfer(a: torch.Tensor, b: torch.Tensor) -> torch.Tensor:
    """Per-object L1 Chamfer distance of point sets a (B, N, 3) and b (B, M, 3): the mean
    nearest distance, averaged over both directions (as `holiscene eval --shapes` measures)."""
    distance = torch.cdist(a, b)
    return 0.5 * (distance.min(dim=2).values.mean(dim=1) + distance.min(dim=1).values.mean(dim=1))
