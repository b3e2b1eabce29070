"""Applying the app's edits to a scene, and keeping people's supports through pipeline re-runs."""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from datetime import datetime

from holiscene_schema import (
    STRUCTURAL_CLASSES,
    STRUCTURAL_SUPPORTERS,
    Edit,
    RemoveSupport,
    RestoreSupport,
    Scene,
    SetLayout,
    SetSupport,
    SupportRelation,
    support_graph_problems,
)

from .layout_edit import LayoutEditError, apply_set_layout, describe_set_layout


class InvalidEditError(ValueError):
    """An edit that names something that does not exist or breaks the support graph."""


def restore_revisions(edits: Sequence[Edit]) -> set[int]:
    """The earlier revisions the edits restore supports from."""
    return {e.from_revision for e in edits if isinstance(e, RestoreSupport)}


def apply_edits(
    scene: Scene,
    edits: Sequence[Edit],
    author: str,
    now: datetime,
    earlier: Mapping[int, Scene] | None = None,
) -> Scene:
    """The scene after the edits, in order; raises InvalidEditError and changes nothing if any
    edit is invalid or the result is not a valid support forest. `earlier` holds the revisions
    named by RestoreSupport edits (restore_revisions)."""
    objects = {o.id: o for o in scene.objects}
    supports = {s.child: s for s in scene.supports}
    for edit in edits:
        if isinstance(edit, SetLayout):
            try:
                scene = apply_set_layout(scene, edit)
            except LayoutEditError as error:
                raise InvalidEditError(f"room layout: {error}") from error
            continue
        child = objects.get(edit.child)
        if child is None:
            raise InvalidEditError(f"no object {edit.child!r} in this scene")
        if child.cls in STRUCTURAL_CLASSES:
            raise InvalidEditError(f"{edit.child!r} is a {child.cls}: structure has no supporter")
        if isinstance(edit, SetSupport):
            if edit.parent not in objects and edit.parent not in STRUCTURAL_SUPPORTERS:
                raise InvalidEditError(
                    f"supporter {edit.parent!r} is neither an object of this scene nor "
                    "floor, wall or ceiling"
                )
            supports[edit.child] = SupportRelation(
                child=edit.child,
                parent=edit.parent,
                type=edit.type,
                source="manual",
                confidence=None,
                author=author,
                time=now,
            )
        elif isinstance(edit, RestoreSupport):
            restored = _restored_support(edit, (earlier or {}).get(edit.from_revision))
            if restored is None:
                supports.pop(edit.child, None)
            elif restored.parent not in objects and restored.parent not in STRUCTURAL_SUPPORTERS:
                raise InvalidEditError(
                    f"supporter {restored.parent!r} of {edit.child!r} in revision "
                    f"{edit.from_revision} is no longer in this scene"
                )
            else:
                supports[edit.child] = restored
        elif isinstance(edit, RemoveSupport):
            if edit.child not in supports:
                raise InvalidEditError(f"object {edit.child!r} has no supporter to remove")
            del supports[edit.child]
    ordered = [supports[o.id] for o in scene.objects if o.id in supports]
    problems = support_graph_problems(list(objects), [(s.child, s.parent) for s in ordered])
    if problems:
        raise InvalidEditError("; ".join(problems))
    return scene.model_copy(update={"supports": ordered})


def _restored_support(edit: RestoreSupport, earlier: Scene | None) -> SupportRelation | None:
    """The child's support in the earlier revision, as it was stored (None: it had none)."""
    if earlier is None:
        raise InvalidEditError(f"no revision {edit.from_revision} to restore from")
    return next((s for s in earlier.supports if s.child == edit.child), None)


def describe_edits(edits: Sequence[Edit]) -> str:
    parts = []
    for edit in edits:
        if isinstance(edit, SetSupport):
            parts.append(f"{edit.child} supported by {edit.parent} ({edit.type})")
        elif isinstance(edit, SetLayout):
            parts.append(describe_set_layout(edit))
        elif isinstance(edit, RestoreSupport):
            parts.append(f"{edit.child} support as in revision {edit.from_revision}")
        else:
            parts.append(f"{edit.child} support removed")
    return "; ".join(parts)


def keep_manual_supports(result: Scene, current: Scene) -> Scene:
    """`result` (a fresh pipeline run) with every manual support of `current` kept.

    People may edit while a pipeline job runs. Their edges win; an automatic edge that would
    now close a cycle falls back to the structural supporter of its type.
    """
    ids = [o.id for o in result.objects]
    manual = [s for s in current.supports if s.source == "manual" and s.child in ids]
    merged = {s.child: s for s in manual}
    for auto in result.supports:
        if auto.child in merged:
            continue
        edges = [(s.child, s.parent) for s in merged.values()] + [(auto.child, auto.parent)]
        if support_graph_problems(ids, edges):
            fallback = "wall" if auto.type == "behind" else "floor"
            auto = auto.model_copy(update={"parent": fallback, "confidence": None})
        merged[auto.child] = auto
    ordered = [merged[i] for i in ids if i in merged]
    return result.model_copy(update={"supports": ordered})
