"""Stages by name, and pipelines built from a list of names."""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from typing import Any, TypeVar

from .base import INPUT_SLOTS, SLOTS, PipelineBuildError, Stage

_REGISTRY: dict[str, type[Stage]] = {}
S = TypeVar("S", bound=type[Stage])


def register_stage(cls: S) -> S:
    unknown = (cls.requires | cls.provides) - SLOTS
    if unknown:
        raise TypeError(f"stage {cls.name!r} names unknown context slots {sorted(unknown)}")
    if cls.name in _REGISTRY:
        raise TypeError(f"stage name {cls.name!r} is registered twice")
    _REGISTRY[cls.name] = cls
    return cls


def registered_stages() -> dict[str, type[Stage]]:
    _load_builtin_stages()
    return dict(_REGISTRY)


def build_stages(
    names: Sequence[str], options: Mapping[str, Mapping[str, Any]] | None = None
) -> list[Stage]:
    """Instantiate stages in order, checking that every required slot is provided earlier."""
    stages_by_name = registered_stages()
    options = options or {}
    unused = set(options) - set(names)
    if unused:
        raise PipelineBuildError(f"options given for stages not in the pipeline: {sorted(unused)}")
    available = set(INPUT_SLOTS)
    stages: list[Stage] = []
    for name in names:
        if name not in stages_by_name:
            raise PipelineBuildError(
                f"unknown stage {name!r}; known stages: {', '.join(sorted(stages_by_name))}"
            )
        cls = stages_by_name[name]
        missing = cls.requires - available
        if missing:
            raise PipelineBuildError(
                f"stage {name!r} requires {sorted(missing)}, which no earlier stage provides"
            )
        stages.append(cls(**dict(options.get(name, {}))))
        available |= cls.provides
    return stages


def _load_builtin_stages() -> None:
    from . import stages  # noqa: F401  (importing registers them)
