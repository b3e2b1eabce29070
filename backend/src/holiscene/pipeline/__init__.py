"""The scene pipeline: typed stages composed by name (see docs/architecture.md, "Data flow")."""

from .base import PipelineBuildError, SceneContext, Stage, StageFailedError
from .registry import registered_stages
from .runner import (
    DEFAULT_STAGES,
    KEPT_LAYOUT_STAGES,
    PLACEMENT_STAGES,
    Pipeline,
    build_pipeline,
)

__all__ = [
    "DEFAULT_STAGES",
    "KEPT_LAYOUT_STAGES",
    "PLACEMENT_STAGES",
    "Pipeline",
    "PipelineBuildError",
    "SceneContext",
    "Stage",
    "StageFailedError",
    "build_pipeline",
    "registered_stages",
]
