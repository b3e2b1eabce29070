"""Test vectors for the room fit: `python -m holiscene.twin_vectors.room_fit` writes
shared_schema/vectors/room_fit.json.

The room fit (layout corners + K + camera height -> camera pitch/roll and the room box) is
written twice, in Python (holiscene.geometry.room_fit) and TypeScript
(frontend/src/geometry/roomFit.ts); both are tested against these vectors. This module is a
development tool: it needs the backend's fit (for the noisy cases' expected output), so it
lives in the backend, not in the contract's package.

Deterministic (one seeded generator). Each case is a random camera in a random room, near the
wall behind it, with the room's 8 corners projected into a 640x480 or 730x530 image (None
behind the camera; corners outside the image stay). Kinds:
- exact: corners projected exactly; expected = the truth they came from.
- noisy: Gaussian pixel noise (sigma 1-2 px); expected = the Python fit's output, which the
  TypeScript fit must reproduce; the truth is stored beside it.
- unseen_wall: only two adjacent vertical room edges are seen, so the input also gives the
  unseen wall's true distance from the camera; exact, expected = the truth.
- error: inputs the fit must refuse; expected.error is part of the message both give.
Run it again after changing both fits together.
"""

from __future__ import annotations

import json
import math
import re
from dataclasses import dataclass
from typing import Any

import numpy as np
from holiscene_schema.scene import BOX_CORNER_SIGNS

from ..core.settings import REPO_ROOT
from ..geometry.boxes import box_corners
from ..geometry.camera import FloatArray, PinholeCamera, rot_y
from ..geometry.room_fit import (
    MIN_DEPTH,
    corner_coverage_problem,
    fit_room,
    project_room_corners,
)

ROOM_FIT_VECTORS = REPO_ROOT / "shared_schema" / "vectors" / "room_fit.json"
SEED = 20260504
COUNTS = {"exact": 20, "noisy": 12, "unseen_wall": 5}

# The scenes' ranges (the hypothesis tests draw from the same).
IMAGE_SIZES = ((640, 480), (730, 530))
HFOV_DEG = (45.0, 75.0)
PRINCIPAL_OFFSET_PX = 8.0  # the principal point is within this of the image centre
ASPECT = (0.98, 1.02)  # fy / fx
ROOM_DEPTH_M = (3.0, 7.0)
ROOM_HEIGHT_M = (2.4, 3.2)
ROOM_WIDTH_M = (3.0, 7.0)
ROOM_YAW_DEG = (-40.0, 40.0)
PITCH_DEG = (0.0, 30.0)
ROLL_DEG = (-10.0, 10.0)
CAMERA_HEIGHT_M = (1.1, 1.7)
BACK_WALL_DISTANCE_M = (0.25, 1.5)
SIDE_WALL_MARGIN_M = 0.4  # nearest the camera gets to a side wall
NOISE_PX = (1.0, 2.0)
# Known corners nearer the camera plane than this project thousands of pixels away, which no
# layout estimator or annotator gives: such scenes are skipped.
MIN_CORNER_DEPTH_M = 0.05

Json = dict[str, Any]


@dataclass(frozen=True)
class RoomScene:
    """A camera in a room, in the parameters a test draws."""

    image_size: tuple[int, int]
    hfov_deg: float
    principal_offset: tuple[float, float]  # principal point minus the image centre, pixels
    aspect: float  # fy / fx
    size: tuple[float, float, float]  # room depth (own x), height, width (own z), metres
    yaw_deg: float
    pitch_deg: float
    roll_deg: float
    camera_height: float
    back_distance: float  # camera to the wall behind it (the room's -x wall)
    left_distance: float  # camera to the room's -z wall

    def K(self) -> FloatArray:
        width, height = self.image_size
        focal = (width / 2) / math.tan(math.radians(self.hfov_deg) / 2)
        return np.array(
            [
                [focal, 0.0, width / 2 + self.principal_offset[0]],
                [0.0, focal * self.aspect, height / 2 + self.principal_offset[1]],
                [0.0, 0.0, 1.0],
            ]
        )

    def center(self) -> FloatArray:
        """The room box's centre in the world (camera) frame."""
        depth, height, width = self.size
        # The room's centre relative to the camera, in the room's axes.
        local = np.array(
            [
                depth / 2 - self.back_distance,
                height / 2 - self.camera_height,
                width / 2 - self.left_distance,
            ]
        )
        result: FloatArray = rot_y(math.radians(self.yaw_deg)) @ local
        return result

    def corners_3d(self) -> FloatArray:
        return box_corners(self.center(), np.array(self.size), self.yaw_deg)

    def corners_2d(self) -> list[list[float] | None]:
        return project_room_corners(self.K(), self.pitch_deg, self.roll_deg, self.corners_3d())

    def wall_distance(self, axis: int, side: int) -> float:
        """Camera to the wall on `side` of the room's own `axis` (0 = x, 2 = z)."""
        near = self.back_distance if axis == 0 else self.left_distance
        return near if side < 0 else self.size[axis] - near

    def nearest_corner_depth(self) -> float:
        """Depth (along the optical axis) of the known corner nearest the camera plane."""
        camera = PinholeCamera(self.K(), self.pitch_deg, self.roll_deg)
        depths = (self.corners_3d() @ camera.world_from_cv)[:, 2]
        return float(depths[depths > MIN_DEPTH].min())

    def fit_input(self) -> Json:
        """fit_room's keyword arguments: with the unseen wall's distance when one is unseen."""
        corners_2d = self.corners_2d()
        unseen = [
            self.wall_distance(axis, side)
            for axis in (0, 2)
            for side in (-1, 1)
            if all(
                c is None
                for c, s in zip(corners_2d, BOX_CORNER_SIGNS, strict=True)
                if s[axis] == side
            )
        ]
        return {
            "K": self.K().tolist(),
            "corners_2d": corners_2d,
            "camera_height": self.camera_height,
            "unseen_wall_distance": unseen[0] if unseen else None,
        }

    def truth(self) -> Json:
        return {
            "pitch_deg": self.pitch_deg,
            "roll_deg": self.roll_deg,
            "room": {
                "center": self.center().tolist(),
                "size": list(self.size),
                "yaw_deg": self.yaw_deg,
            },
            "corners_3d": self.corners_3d().tolist(),
            "rms_px": 0.0,
        }


def sample_scene(rng: np.random.Generator) -> RoomScene:
    size = (rng.uniform(*ROOM_DEPTH_M), rng.uniform(*ROOM_HEIGHT_M), rng.uniform(*ROOM_WIDTH_M))
    return RoomScene(
        image_size=IMAGE_SIZES[int(rng.integers(len(IMAGE_SIZES)))],
        hfov_deg=rng.uniform(*HFOV_DEG),
        principal_offset=(
            rng.uniform(-PRINCIPAL_OFFSET_PX, PRINCIPAL_OFFSET_PX),
            rng.uniform(-PRINCIPAL_OFFSET_PX, PRINCIPAL_OFFSET_PX),
        ),
        aspect=rng.uniform(*ASPECT),
        size=size,
        yaw_deg=rng.uniform(*ROOM_YAW_DEG),
        pitch_deg=rng.uniform(*PITCH_DEG),
        roll_deg=rng.uniform(*ROLL_DEG),
        camera_height=rng.uniform(*CAMERA_HEIGHT_M),
        back_distance=rng.uniform(*BACK_WALL_DISTANCE_M),
        left_distance=rng.uniform(SIDE_WALL_MARGIN_M, size[2] - SIDE_WALL_MARGIN_M),
    )


def fit_output(fit_input: Json) -> Json:
    """The Python fit's result, in the vectors' form."""
    fit = fit_room(**fit_input)
    return {
        "pitch_deg": fit.pitch_deg,
        "roll_deg": fit.roll_deg,
        "room": {
            "center": fit.room.center.tolist(),
            "size": fit.room.size.tolist(),
            "yaw_deg": fit.room.yaw_deg,
        },
        "corners_3d": fit.corners_3d.tolist(),
        "rms_px": fit.rms_px,
    }


def _with_noise(fit_input: Json, sigma: float, rng: np.random.Generator) -> Json:
    corners = [
        None if c is None else (np.array(c) + rng.normal(0.0, sigma, 2)).tolist()
        for c in fit_input["corners_2d"]
    ]
    return {**fit_input, "corners_2d": corners}


def _only(fit_input: Json, keep: set[int]) -> Json:
    """The input with only the corners in keep known."""
    corners = [c if i in keep else None for i, c in enumerate(fit_input["corners_2d"])]
    return {**fit_input, "corners_2d": corners}


def _error_cases(good: Json) -> list[Json] | None:
    """Inputs the fit must refuse, made from a good input with its four front corners and a
    back vertical edge known; None for an input without them."""
    known = {i for i, c in enumerate(good["corners_2d"]) if c is not None}
    back = next((i for i in (0, 3) if {i, i + 4} <= known), None)  # a whole back vertical edge
    if not {1, 2, 5, 6} <= known or back is None:
        return None
    across = 2 if back == 0 else 1  # the front vertical edge diagonally across the floor plan
    mirrored = [good["corners_2d"][i] for i in (3, 2, 1, 0, 7, 6, 5, 4)]  # z signs swapped
    cases = [
        ("too-few-corners", _only(good, {1, 2, 5}), "fewer than 4 known corners"),
        ("one-vertical-edge", _only(good, {1, 5, 2, back}), "fewer than two vertical room edges"),
        (
            "opposite-edges",
            _only(good, {back, back + 4, across, across + 4}),
            "only two opposite vertical room edges",
        ),
        ("wall-unseen-no-prior", _only(good, {1, 2, 5, 6}), "a wall has no known corner"),
        ("seven-corners", {**good, "corners_2d": good["corners_2d"][:7]}, "expected 8 layout"),
        ("mirrored-order", {**good, "corners_2d": mirrored}, "the room comes out inside out"),
        ("singular-K", {**good, "K": [[1.0, 0, 0], [0, 0, 0], [0, 0, 1]]}, "K must be invertible"),
        ("zero-camera-height", {**good, "camera_height": 0.0}, "camera_height must be a positive"),
    ]
    for name, data, message in cases:
        try:
            fit_room(**data)
        except ValueError as error:
            assert message in str(error), f"{name}: {error}"
        else:
            raise AssertionError(f"{name}: the fit accepted it")
    return [
        {"name": f"error-{name}", "kind": "error", "input": data, "expected": {"error": message}}
        for name, data, message in cases
    ]


def generate() -> Json:
    rng = np.random.default_rng(SEED)
    cases: list[Json] = []
    counts = dict.fromkeys(COUNTS, 0)
    errors: list[Json] | None = None
    while any(counts[kind] < COUNTS[kind] for kind in COUNTS):
        scene = sample_scene(rng)
        if scene.nearest_corner_depth() < MIN_CORNER_DEPTH_M:
            continue
        fit_input = scene.fit_input()
        if corner_coverage_problem(fit_input["corners_2d"]) is None:  # interleave the kinds
            kind = min(("exact", "noisy"), key=lambda k: counts[k] / COUNTS[k])
        elif fit_input["unseen_wall_distance"] is not None:
            kind = "unseen_wall"
        else:
            continue
        if counts[kind] >= COUNTS[kind]:
            continue
        errors = errors or _error_cases(fit_input)
        case: Json = {"input": fit_input, "expected": scene.truth()}
        if kind == "noisy":
            sigma = rng.uniform(*NOISE_PX)
            noisy_input = _with_noise(fit_input, sigma, rng)
            case = {"input": noisy_input, "expected": fit_output(noisy_input)}
            case |= {"truth": scene.truth(), "noise_px": sigma}
        cases.append({"name": f"{kind}-{counts[kind]:02d}", "kind": kind, **case})
        counts[kind] += 1
    assert errors, "no scene to make the error cases from"
    return {
        "about": "Test vectors of the room fit: see holiscene/twin_vectors/room_fit.py",
        "seed": SEED,
        "box_corner_signs": [list(signs) for signs in BOX_CORNER_SIGNS],
        "cases": cases + errors,
    }


def to_json(data: Json) -> str:
    """Indented JSON with innermost lists (points, matrix rows) on one line each."""
    text = json.dumps(data, indent=2)
    return (
        re.sub(r"\[\s+([^\[\]{}]*?)\s+\]", lambda m: "[" + re.sub(r",\s+", ", ", m[1]) + "]", text)
        + "\n"
    )


if __name__ == "__main__":
    ROOM_FIT_VECTORS.parent.mkdir(exist_ok=True)
    ROOM_FIT_VECTORS.write_text(to_json(generate()))
    print(f"wrote {ROOM_FIT_VECTORS}")
