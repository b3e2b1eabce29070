"""A pipeline: stages run in order on one context, timed, with progress reported."""

from __future__ import annotations

import time
from collections.abc import Callable, Mapping, Sequence
from typing import Any

from holiscene_schema import StageRun

from .base import SceneContext, Stage
from .registry import build_stages

# The stages of `holiscene infer` and of the server's pipeline jobs, in order.
DEFAULT_STAGES: tuple[str, ...] = (
    "objects_from_detector",
    "intrinsics",
    "masks_grabcut",
    "layout_from_lines",
    "layout_from_depth",
    "supports_from_network",
    "heights_by_metrology",
    "placement",
    "boxes_by_refiner",
    "layout_holds_hung_objects",
    "boxes_from_depth",
    "shapes_fit",
    "shapes_by_mesh_net",
    "shape_completion",
    "scene_mesh",
)

# A placement job: the stages after the room layout, on a stored scene whose layout (or
# supports) a person changed. Heights are measured again: they depend on the camera's pitch
# and roll and on the room's height line. With depth, the boxes are measured from it again and
# the shapes completed, as in the full pipeline (the depth stages are skipped without).
PLACEMENT_STAGES: tuple[str, ...] = (
    "scene_from_revision",
    "heights_by_metrology",
    "placement",
    "boxes_by_refiner",
    "boxes_from_depth",
    "shapes_fit",
    "shapes_by_mesh_net",
    "shape_completion",
    "scene_mesh",
)

# A full re-run of a scene whose room layout a person set: that layout and the camera fitted
# to it are kept (as people's supports are), every other stage runs again around them.
# (The depth's room would replace it, so the depth refines only the boxes.)
KEPT_LAYOUT_STAGES: tuple[str, ...] = tuple(
    "layout_from_revision" if name == "layout_from_lines" else name
    for name in DEFAULT_STAGES
    if name != "layout_from_depth"
)

ProgressCallback = Callable[[str, float], None]


class Pipeline:
    def __init__(self, stages: Sequence[Stage]) -> None:
        self.stages = list(stages)

    @property
    def names(self) -> list[str]:
        return [s.name for s in self.stages]

    def run(self, ctx: SceneContext, progress: ProgressCallback | None = None) -> list[StageRun]:
        """Run every stage; `progress(stage_name, fraction_done)` is called before each one."""
        runs: list[StageRun] = []
        for index, stage in enumerate(self.stages):
            if stage.needs_depth and ctx.depth is None:
                continue
            if stage.single_photo_only and ctx.depth is not None:
                continue
            if progress:
                progress(stage.name, index / len(self.stages))
            start = time.perf_counter()
            stage.run(ctx)
            warning = ctx.notes.get(stage.name) or None
            runs.append(
                StageRun(
                    name=stage.name,
                    seconds=round(time.perf_counter() - start, 4),
                    note=warning or ctx.reports.get(stage.name),
                    warning=warning is not None,
                )
            )
        if progress:
            progress("done", 1.0)
        return runs


def build_pipeline(
    names: Sequence[str] = DEFAULT_STAGES, options: Mapping[str, Mapping[str, Any]] | None = None
) -> Pipeline:
    return Pipeline(build_stages(names, options))
