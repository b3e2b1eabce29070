"""Intrinsics: given with the photo, or assumed from a typical field of view."""

from __future__ import annotations

import numpy as np

from ...geometry.camera import default_intrinsics
from ..base import SceneContext, Stage
from ..registry import register_stage

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
