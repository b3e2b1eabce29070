"""The layout estimation network (LEN) and the object detection network (ODN) of thesis Ch. 5
(Total3DUnderstanding), smaller, on the COCO backbone's features (PyTorch, training only).

The LEN reads the whole photo's features (`features.ROOM_CHANNELS` on the deep grid) and the
camera's intrinsics, and gives the camera's pitch and roll and the room (`outputs`). The ODN
reads each object's pooled features, 2D box and class with the LEN's code of the room, then
the object relation module (`learning/relation.py`) over the photo's other objects, and gives
each box. Trained together (`joint_loss`): each estimate's own loss, plus the thesis's
cooperative losses: the corner loss (the decoded 3D box's corners against the true ones) and
the physical violation (corners outside the estimated room). Its third, the global alignment
of meshes with the room, needs meshes, which these networks do not make.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import torch
from holiscene_schema import BOX_CORNER_SIGNS
from torch import nn
from torch.nn import functional

from ..box_refiner.features import PAIR_FEATURES
from ..relation import RelationModule
from .bins import LOG_DISTANCE_BINS, OBJECT_YAW_BINS, ROOM_YAW_BINS, Bins
from .features import (
    CAMERA_INPUTS,
    OBJECT_APPEARANCE,
    OBJECT_GEOMETRY,
    OBJECT_INPUTS,
    ROOM_CHANNELS,
)
from .outputs import OBJECT_OUTPUTS, OBJECT_SLICES, ROOM_OUTPUTS, ROOM_SLICES

STANDARDISED = OBJECT_APPEARANCE + OBJECT_GEOMETRY  # the class one-hot is left as it is
CORNER_WEIGHT = 0.5
VIOLATION_WEIGHT = 0.2


class SceneNet(nn.Module):
    room_mean: torch.Tensor
    room_std: torch.Tensor
    object_mean: torch.Tensor
    object_std: torch.Tensor

    def __init__(
        self,
        room_mean: np.ndarray,
        room_std: np.ndarray,
        object_mean: np.ndarray,
        object_std: np.ndarray,
        grid: int = 16,
        hidden: int = 256,
    ) -> None:
        super().__init__()
        # Standardisation baked in, so the exported model reads raw features.
        self.register_buffer(
            "room_mean", torch.tensor(room_mean, dtype=torch.float32).view(1, -1, 1, 1)
        )
        self.register_buffer(
            "room_std", torch.tensor(room_std, dtype=torch.float32).view(1, -1, 1, 1)
        )
        self.register_buffer("object_mean", torch.tensor(object_mean, dtype=torch.float32))
        self.register_buffer("object_std", torch.tensor(object_std, dtype=torch.float32))
        self.room_encoder = nn.Sequential(
            nn.Conv2d(ROOM_CHANNELS, 64, 1),
            nn.ReLU(),
            nn.Conv2d(64, 32, 3, stride=2, padding=1),
            nn.ReLU(),
            nn.Flatten(),
            nn.Dropout(0.3),
        )
        cells = 32 * ((grid + 1) // 2) ** 2
        self.room_code = nn.Sequential(
            nn.Linear(cells + CAMERA_INPUTS, hidden),
            nn.ReLU(),
            nn.Linear(hidden, hidden),
            nn.ReLU(),
        )
        self.room_head = nn.Linear(hidden, ROOM_OUTPUTS)
        self.object_encode = nn.Sequential(
            nn.Dropout(0.3),
            nn.Linear(OBJECT_INPUTS + hidden, hidden),
            nn.ReLU(),
            nn.Linear(hidden, hidden),
            nn.ReLU(),
        )
        self.relation = RelationModule(hidden, 4, PAIR_FEATURES)
        self.object_head = nn.Sequential(
            nn.Linear(2 * hidden, hidden), nn.ReLU(), nn.Linear(hidden, OBJECT_OUTPUTS)
        )

    def forward(
        self, room: torch.Tensor, camera: torch.Tensor, objects: torch.Tensor, pairs: torch.Tensor
    ) -> tuple[torch.Tensor, torch.Tensor]:
        """room (B, ROOM_CHANNELS, G, G), camera (B, CAMERA_INPUTS), objects (B, n,
        OBJECT_INPUTS), pairs (B, n, n, PAIR_FEATURES) -> the LEN's rows (B, ROOM_OUTPUTS) and
        the ODN's (B, n, OBJECT_OUTPUTS). Padding objects (all zero) are ignored by the losses;
        the relation module attends to them a little, as to any object (the runtime has none)."""
        room_features = (room - self.room_mean) / self.room_std
        code = self.room_code(torch.cat([self.room_encoder(room_features), camera], dim=1))
        standardised = (objects[..., :STANDARDISED] - self.object_mean) / self.object_std
        inputs = torch.cat([standardised, objects[..., STANDARDISED:]], dim=-1)
        n = objects.shape[1]
        scene = code[:, None, :].expand(-1, n, -1)
        encoded = self.object_encode(torch.cat([inputs, scene], dim=-1))
        context = self.relation(encoded, pairs)
        rows = self.object_head(torch.cat([encoded, context], dim=-1))
        return self.room_head(code), rows


@dataclass
class Batch:
    """Padded photos: inputs, then targets (`train.batch_of` builds them)."""

    room: torch.Tensor
    camera: torch.Tensor
    objects: torch.Tensor
    pairs: torch.Tensor
    valid: torch.Tensor  # (B, n) 1 for an object with targets, 0 for padding
    room_bins: dict[str, tuple[torch.Tensor, torch.Tensor]]  # name -> (bin, offset), (B,)
    log_height: torch.Tensor  # (B,)
    log_distances: torch.Tensor  # (B, 5)
    centre_offset: torch.Tensor  # (B, n, 2)
    object_bins: dict[str, tuple[torch.Tensor, torch.Tensor]]  # (B, n) each
    log_size: torch.Tensor  # (B, n, 3)
    # For the cooperative losses: per object its 2D box (x1, y1, x2, y2, pixels), typical size,
    # true corners (n, 8, 3); per photo the true camera's pixel -> world ray matrix (3, 3).
    bbox: torch.Tensor
    typical_size: torch.Tensor
    true_corners: torch.Tensor
    world_from_pixel: torch.Tensor


def _bin_loss(
    rows: torch.Tensor,
    slices: dict[str, slice],
    name: str,
    target: tuple[torch.Tensor, torch.Tensor],
) -> torch.Tensor:
    """Per row: the bin's cross-entropy plus the offset's error in the true bin."""
    scores, offsets = rows[..., slices[f"{name}_scores"]], rows[..., slices[f"{name}_offsets"]]
    index, offset = target
    flat = scores.reshape(-1, scores.shape[-1])
    classification = functional.cross_entropy(flat, index.reshape(-1), reduction="none")
    chosen = torch.gather(offsets, -1, index[..., None])[..., 0]
    return classification.reshape(index.shape) + functional.smooth_l1_loss(
        chosen, offset, reduction="none", beta=0.1
    )


def _in_true_bin(
    rows: torch.Tensor, slices: dict[str, slice], name: str, bins: Bins, index: torch.Tensor
) -> torch.Tensor:
    """The value the row gives in the true bin (what the cooperative losses decode with)."""
    offsets = rows[..., slices[f"{name}_offsets"]]
    chosen = torch.gather(offsets, -1, index[..., None])[..., 0]
    return bins.low + (index.float() + 0.5 + chosen) * bins.width


_SIGNS = torch.tensor(BOX_CORNER_SIGNS, dtype=torch.float32)


def decoded_corners(rows: torch.Tensor, batch: Batch) -> torch.Tensor:
    """Each object's 3D box corners (B, n, 8, 3) from the ODN's rows with the true camera."""
    box = batch.bbox
    size_2d = (box[..., 2:] - box[..., :2]).clamp(min=1.0)
    pixel = (box[..., :2] + box[..., 2:]) / 2 + rows[..., OBJECT_SLICES["centre_offset"]] * size_2d
    homogeneous = torch.cat([pixel, torch.ones_like(pixel[..., :1])], dim=-1)
    ray = torch.einsum("bij,bnj->bni", batch.world_from_pixel, homogeneous)
    ray = ray / ray.norm(dim=-1, keepdim=True)
    index = batch.object_bins["distance"][0]
    distance = torch.exp(_in_true_bin(rows, OBJECT_SLICES, "distance", LOG_DISTANCE_BINS, index))
    centre = ray * distance[..., None]
    size = batch.typical_size * torch.exp(rows[..., OBJECT_SLICES["log_size"]])
    yaw_index = batch.object_bins["yaw"][0]
    azimuth = torch.atan2(-centre[..., 2], centre[..., 0])
    yaw = (
        torch.deg2rad(_in_true_bin(rows, OBJECT_SLICES, "yaw", OBJECT_YAW_BINS, yaw_index))
        + azimuth
    )
    local = _SIGNS.to(rows.device) * size[..., None, :] / 2  # (B, n, 8, 3)
    cos, sin = torch.cos(yaw)[..., None], torch.sin(yaw)[..., None]
    x = local[..., 0] * cos + local[..., 2] * sin
    z = -local[..., 0] * sin + local[..., 2] * cos
    corners: torch.Tensor = torch.stack([x, local[..., 1], z], dim=-1) + centre[..., None, :]
    return corners


def _violation(room_rows: torch.Tensor, corners: torch.Tensor, batch: Batch) -> torch.Tensor:
    """How far (metres) each object's corners reach outside the LEN's room: (B, n)."""
    yaw_index = batch.room_bins["yaw"][0]
    yaw = torch.deg2rad(_in_true_bin(room_rows, ROOM_SLICES, "yaw", ROOM_YAW_BINS, yaw_index))
    height = torch.exp(room_rows[:, ROOM_SLICES["log_height"]][:, 0])
    front, back, left, right, ceiling = (
        torch.exp(room_rows[:, ROOM_SLICES["log_distances"]]) * height[:, None]
    ).unbind(-1)
    cos, sin = torch.cos(yaw)[:, None, None], torch.sin(yaw)[:, None, None]
    along = corners[..., 0] * cos - corners[..., 2] * sin  # room x = (cos, 0, -sin)
    across = corners[..., 0] * sin + corners[..., 2] * cos  # room z = (sin, 0, cos)
    up = corners[..., 1]

    def beyond(value: torch.Tensor, limit: torch.Tensor) -> torch.Tensor:
        return functional.relu(value - limit[:, None, None])

    outside = (
        beyond(along, front) + beyond(-along, back) + beyond(across, right)
        + beyond(-across, left) + beyond(up, ceiling) + beyond(-up, height)
    )  # fmt: skip
    result: torch.Tensor = outside.mean(dim=-1)
    return result


def joint_loss(net: SceneNet, batch: Batch) -> tuple[torch.Tensor, dict[str, float]]:
    """The LEN's and the ODN's losses with the cooperative ones; the parts for the curve."""
    room_rows, object_rows = net(batch.room, batch.camera, batch.objects, batch.pairs)
    room_loss = sum(
        _bin_loss(room_rows, ROOM_SLICES, name, batch.room_bins[name]).mean()
        for name in ("pitch", "roll", "yaw")
    )
    room_loss = room_loss + functional.smooth_l1_loss(
        room_rows[:, ROOM_SLICES["log_height"]][:, 0], batch.log_height, beta=0.1
    )
    room_loss = room_loss + functional.smooth_l1_loss(
        room_rows[:, ROOM_SLICES["log_distances"]], batch.log_distances, beta=0.1
    )
    valid = batch.valid
    count = valid.sum().clamp(min=1.0)

    def per_object(values: torch.Tensor) -> torch.Tensor:
        return (values * valid).sum() / count

    offset_error = functional.smooth_l1_loss(
        object_rows[..., OBJECT_SLICES["centre_offset"]],
        batch.centre_offset,
        reduction="none",
        beta=0.1,
    ).sum(-1)
    size_error = functional.smooth_l1_loss(
        object_rows[..., OBJECT_SLICES["log_size"]], batch.log_size, reduction="none", beta=0.1
    ).sum(-1)
    object_loss = per_object(
        offset_error
        + size_error
        + _bin_loss(object_rows, OBJECT_SLICES, "distance", batch.object_bins["distance"])
        + _bin_loss(object_rows, OBJECT_SLICES, "yaw", batch.object_bins["yaw"])
    )
    corners = decoded_corners(object_rows, batch)
    corner_error = (corners - batch.true_corners).norm(dim=-1).mean(-1)
    corner_loss = per_object(corner_error.clamp(max=5.0))
    violation = per_object(_violation(room_rows, corners, batch).clamp(max=5.0))
    total = room_loss + object_loss + CORNER_WEIGHT * corner_loss + VIOLATION_WEIGHT * violation
    parts = {
        "room": float(room_loss.detach()),
        "objects": float(object_loss.detach()),
        "corners_m": float(corner_loss.detach()),
        "violation_m": float(violation.detach()),
    }
    return total, parts


def export_scene_net(net: SceneNet, path: str, grid: int = 16) -> None:
    """The two networks as one ONNX file: inputs room, camera, objects, pairs (one photo, any
    number of objects); outputs `room` (1, ROOM_OUTPUTS) and `objects` (1, n, OBJECT_OUTPUTS)."""
    net.eval()
    n = 3
    example = (
        torch.zeros(1, ROOM_CHANNELS, grid, grid),
        torch.zeros(1, CAMERA_INPUTS),
        torch.zeros(1, n, OBJECT_INPUTS),
        torch.zeros(1, n, n, PAIR_FEATURES),
    )
    torch.onnx.export(
        net,
        example,
        path,
        input_names=["room", "camera", "objects", "pairs"],
        output_names=["room_rows", "object_rows"],
        dynamic_axes={"objects": {1: "n"}, "pairs": {1: "n", 2: "n"}, "object_rows": {1: "n"}},
        opset_version=17,
        dynamo=False,
    )
