"""Intrinsics (given or assumed) and pitch and roll from the vertical vanishing point."""

from __future__ import annotations

import numpy as np
from holiscene_schema import Camera

from ...geometry.camera import default_intrinsics, pitch_roll_from_up_direction
from ...geometry.lines import detect_segments
from ...geometry.vanishing import vertical_vanishing_point
from ..base import SceneContext, Stage, required
from ..registry import register_stage

# Typical eye level of a hand-held or tripod capture in SUN RGB-D-like photos. A prior, not a
# measurement: metric sizes scale with it (a camera really at 1.0 m or 1.6 m makes every
# length about 25% wrong).
CAMERA_HEIGHT_PRIOR_M = 1.3
ASSUMED_HFOV_DEG = 60.0


@register_stage
class Intrinsics(Stage):
    name = "intrinsics"
    requires = frozenset({"image", "given_K"})
    provides = frozenset({"intrinsics"})

    def run(self, ctx: SceneContext) -> None:
        if ctx.given_K is not None:
            ctx.intrinsics = (np.asarray(ctx.given_K, dtype=float), "given")
            return
        ctx.intrinsics = (default_intrinsics(ctx.width, ctx.height, ASSUMED_HFOV_DEG), "assumed")
        ctx.notes[self.name] = (
            f"no cam_K.txt: assumed a {ASSUMED_HFOV_DEG:.0f} degree horizontal field of view"
        )


@register_stage
class CameraFromVerticalLines(Stage):
    name = "camera_from_vertical_lines"
    requires = frozenset({"image", "intrinsics"})
    provides = frozenset({"camera"})

    def run(self, ctx: SceneContext) -> None:
        K, source = required(ctx.intrinsics, "intrinsics")
        vp = vertical_vanishing_point(detect_segments(ctx.image))
        pitch = roll = None
        if vp is None:
            ctx.notes[self.name] = "too few vertical lines: pitch and roll unknown"
        else:
            up = np.linalg.solve(K, vp).astype(np.float64)
            pitch, roll = (round(angle, 3) for angle in pitch_roll_from_up_direction(up))
        ctx.camera = Camera(
            K=K.tolist(),
            K_source=source,
            pitch_deg=pitch,
            roll_deg=roll,
            height_m=CAMERA_HEIGHT_PRIOR_M,
            height_source="prior",
            note=ctx.notes.get(self.name),
        )
