"""Applying the app's edits to a scene, and keeping people's supports through pipeline re-runs
(their objects are kept by pipeline.people.keep_people_objects, inside the run)."""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from datetime import datetime

import numpy as np
from holiscene_schema import (
    STRUCTURAL_CLASSES,
    STRUCTURAL_SUPPORT_TYPES,
    STRUCTURAL_SUPPORTERS,
    AddObject,
    Edit,
    ObjectEdit,
    RemovedObject,
    RemoveObject,
    RemoveSupport,
    RestoreObject,
    RestoreScene,
    RestoreSupport,
    Scene,
    SceneObject,
    SetBbox,
    SetClass,
    SetLayout,
    SetMask,
    SetSupport,
    SupportRelation,
    support_graph_problems,
)

from ..core.errors import DomainError
from .layout import LayoutEditError, apply_set_layout, describe_set_layout
from .objects import (
    ObjectEditError,
    new_object,
    remove_object,
    restore_object,
    with_bbox,
    with_class,
    with_mask,
)

SupportEdit = SetSupport | RemoveSupport | RestoreSupport
OBJECT_EDITS = (AddObject, RemoveObject, SetClass, SetBbox, SetMask, RestoreObject)


class InvalidEditError(DomainError, ValueError):
    """An edit that names something that does not exist or breaks the support graph."""

    def detail(self) -> str:
        return f"invalid edit: {self}"


def restore_revisions(edits: Sequence[Edit]) -> set[int]:
    """The earlier revisions the edits restore supports, objects or the whole scene from."""
    restoring = RestoreSupport | RestoreObject | RestoreScene
    return {e.from_revision for e in edits if isinstance(e, restoring)}


def restored_scene_revision(edits: Sequence[Edit]) -> int | None:
    """The revision the last restore_scene of the edits restores (None: none does)."""
    restores = [e.from_revision for e in edits if isinstance(e, RestoreScene)]
    return restores[-1] if restores else None


def needs_photo(edits: Sequence[Edit]) -> bool:
    """Whether applying the edits may need the scene's photo (to cut a mask in a box)."""
    return any(
        (isinstance(e, AddObject) and e.mask is None) or isinstance(e, SetBbox) for e in edits
    )


@dataclass
class _Draft:
    """The scene being edited: its objects and their supports by id, in the scene's order."""

    scene: Scene
    objects: dict[str, SceneObject]
    supports: dict[str, SupportRelation]
    removed: list[RemovedObject]

    @classmethod
    def of(cls, scene: Scene) -> _Draft:
        objects = {o.id: o for o in scene.objects}
        supports = {s.child: s for s in scene.supports}
        return cls(scene, objects, supports, list(scene.removed_by_person))

    def result(self) -> Scene:
        """The edited scene; InvalidEditError when its supports are not a valid forest."""
        objects = list(self.objects.values())
        ordered = [self.supports[o.id] for o in objects if o.id in self.supports]
        edges = [(s.child, s.parent) for s in ordered]
        problems = support_graph_problems([o.id for o in objects], edges)
        if problems:
            raise InvalidEditError("; ".join(problems))
        update = {"objects": objects, "supports": ordered, "removed_by_person": self.removed}
        return self.scene.model_copy(update=update)


def apply_edits(
    scene: Scene,
    edits: Sequence[Edit],
    author: str,
    now: datetime,
    earlier: Mapping[int, Scene] | None = None,
    photo: np.ndarray | None = None,
) -> Scene:
    """The scene after the edits, in order; raises InvalidEditError and changes nothing if any
    edit is invalid or the result is not a valid support forest. `earlier` holds the revisions
    named by RestoreSupport and RestoreObject edits (restore_revisions); `photo`, the scene's
    RGB photo, is needed to cut masks in boxes (needs_photo)."""
    draft = _Draft.of(scene)
    for edit in edits:
        if isinstance(edit, RestoreScene):
            draft = _Draft.of(_restored_scene(draft.scene, edit, earlier or {}))
        elif isinstance(edit, SetLayout):
            draft.scene = _with_layout(draft.scene, edit)
        elif isinstance(edit, OBJECT_EDITS):
            _apply_object_edit(draft, edit, photo, earlier or {})
        else:
            _apply_support_edit(draft, edit, author, now, earlier or {})
    return draft.result()


def _restored_scene(scene: Scene, edit: RestoreScene, earlier: Mapping[int, Scene]) -> Scene:
    """The earlier revision's scene on this scene's photo: what people and the pipeline made
    goes back, the inputs (photo, depth) and the name stay."""
    restored = earlier.get(edit.from_revision)
    if restored is None:
        raise InvalidEditError(f"no revision {edit.from_revision} to restore the scene from")
    return restored.model_copy(
        update={"name": scene.name, "image": scene.image, "depth": scene.depth}
    )


def _with_layout(scene: Scene, edit: SetLayout) -> Scene:
    try:
        return apply_set_layout(scene, edit)
    except LayoutEditError as error:
        raise InvalidEditError(f"room layout: {error}") from error


def _apply_object_edit(
    draft: _Draft, edit: ObjectEdit, photo: np.ndarray | None, earlier: Mapping[int, Scene]
) -> None:
    image = draft.scene.image
    try:
        if isinstance(edit, AddObject):
            taken = set(draft.objects)
            draft.objects[edit.id] = new_object(edit, image, taken, photo)
        elif isinstance(edit, RemoveObject):
            gone = draft.objects.get(edit.id)
            remove_object(edit.id, draft.objects, draft.supports)
            if gone is not None:  # remembered, so a pipeline re-run leaves it out
                draft.removed.append(RemovedObject(id=gone.id, cls=gone.cls, bbox=gone.bbox))
        elif isinstance(edit, RestoreObject):
            scene = earlier.get(edit.from_revision)
            if scene is None:
                raise ObjectEditError(f"no revision {edit.from_revision} to restore from")
            draft.objects = restore_object(edit.id, scene, draft.objects, draft.supports)
            draft.removed = [r for r in draft.removed if r.id != edit.id] + [
                r for r in scene.removed_by_person if r.id == edit.id
            ]
        else:
            obj = draft.objects.get(edit.id)
            if obj is None:
                raise ObjectEditError(f"no object {edit.id!r} in this scene")
            if isinstance(edit, SetClass):
                changed = with_class(obj, edit.cls)
            elif isinstance(edit, SetBbox):
                changed = with_bbox(obj, edit.bbox, image, photo)
            else:
                changed = with_mask(obj, edit.mask, image)
            draft.objects[edit.id] = changed
    except ObjectEditError as error:
        raise InvalidEditError(str(error)) from error
    _check_structure_unsupported(draft, edit.id)


def _check_structure_unsupported(draft: _Draft, object_id: str) -> None:
    """An object that became structure (a wall, floor or ceiling class) has no supporter."""
    obj = draft.objects.get(object_id)
    if obj is not None and obj.cls in STRUCTURAL_CLASSES and object_id in draft.supports:
        del draft.supports[object_id]


def _apply_support_edit(
    draft: _Draft,
    edit: SupportEdit,
    author: str,
    now: datetime,
    earlier: Mapping[int, Scene],
) -> None:
    _check_child(draft, edit.child)
    if isinstance(edit, SetSupport):
        _check_supporter(draft, edit.parent)
        _check_structural_type(edit.parent, edit.type)
        draft.supports[edit.child] = SupportRelation(
            child=edit.child,
            parent=edit.parent,
            type=edit.type,
            source="manual",
            confidence=None,
            author=author,
            time=now,
        )
    elif isinstance(edit, RestoreSupport):
        _restore_support(draft, edit, earlier.get(edit.from_revision))
    elif edit.child not in draft.supports:
        raise InvalidEditError(f"object {edit.child!r} has no supporter to remove")
    else:
        del draft.supports[edit.child]


def _check_child(draft: _Draft, child_id: str) -> None:
    child = draft.objects.get(child_id)
    if child is None:
        raise InvalidEditError(f"no object {child_id!r} in this scene")
    if child.cls in STRUCTURAL_CLASSES:
        raise InvalidEditError(f"{child_id!r} is a {child.cls}: structure has no supporter")


def _check_supporter(draft: _Draft, parent: str) -> None:
    if parent not in draft.objects and parent not in STRUCTURAL_SUPPORTERS:
        raise InvalidEditError(
            f"supporter {parent!r} is neither an object of this scene nor floor, wall or ceiling"
        )


def _check_structural_type(parent: str, support_type: str) -> None:
    required = STRUCTURAL_SUPPORT_TYPES.get(parent)
    if required is not None and support_type != required:
        raise InvalidEditError(
            f"the {parent} holds objects up from {required} only, not from {support_type}"
        )


def _restore_support(draft: _Draft, edit: RestoreSupport, earlier: Scene | None) -> None:
    restored = _restored_support(edit, earlier)
    if restored is None:
        draft.supports.pop(edit.child, None)
    elif restored.parent not in draft.objects and restored.parent not in STRUCTURAL_SUPPORTERS:
        raise InvalidEditError(
            f"supporter {restored.parent!r} of {edit.child!r} in revision "
            f"{edit.from_revision} is no longer in this scene"
        )
    else:
        draft.supports[edit.child] = restored


def _restored_support(edit: RestoreSupport, earlier: Scene | None) -> SupportRelation | None:
    """The child's support in the earlier revision, as it was stored (None: it had none)."""
    if earlier is None:
        raise InvalidEditError(f"no revision {edit.from_revision} to restore from")
    return next((s for s in earlier.supports if s.child == edit.child), None)


# Objects named in a revision's summary for the supporters confirmed as guessed.
CONFIRMED_NAMED = 6


def describe_edits(edits: Sequence[Edit], before: Scene | None = None) -> str:
    """The revision's one-line summary. A supporter set to what `before` (the revision edited)
    already had is a guess confirmed: counted at the end, so the changes a reviewer must look
    at come first and are not lost among a whole scene's confirmations."""
    held: set[tuple[str, str, str]] = (
        {(s.child, s.parent, s.type) for s in before.supports} if before else set()
    )
    confirmed = [e.child for e in edits if isinstance(e, SetSupport) and _confirms(e, held)]
    parts = [_describe_edit(e) for e in edits if not _confirms(e, held)]
    if confirmed:
        named = ", ".join(confirmed[:CONFIRMED_NAMED])
        more = (
            f" and {len(confirmed) - CONFIRMED_NAMED} more"
            if len(confirmed) > CONFIRMED_NAMED
            else ""
        )
        guesses = "supporter" if len(confirmed) == 1 else "supporters"
        parts.append(f"{len(confirmed)} {guesses} confirmed as they were ({named}{more})")
    return "; ".join(parts)


def _confirms(edit: Edit, held: set[tuple[str, str, str]]) -> bool:
    return isinstance(edit, SetSupport) and (edit.child, edit.parent, edit.type) in held


def _describe_edit(edit: Edit) -> str:
    if isinstance(edit, SetSupport):
        return f"{edit.child} supported by {edit.parent} ({edit.type})"
    if isinstance(edit, SetLayout):
        return describe_set_layout(edit)
    if isinstance(edit, RestoreSupport):
        return f"{edit.child} support as in revision {edit.from_revision}"
    if isinstance(edit, AddObject):
        return f"{edit.id} added ({edit.cls}, {edit.source})"
    if isinstance(edit, RemoveObject):
        return f"{edit.id} removed"
    if isinstance(edit, SetClass):
        return f"{edit.id} is a {edit.cls}"
    if isinstance(edit, SetBbox):
        return f"{edit.id} box set"
    if isinstance(edit, SetMask):
        return f"{edit.id} mask drawn"
    if isinstance(edit, RestoreObject):
        # An undone removal reads as this too: say the object came back.
        return f"{edit.id} back, as revision {edit.from_revision} had it"
    if isinstance(edit, RestoreScene):
        return f"the scene as in revision {edit.from_revision}"
    return f"{edit.child} support removed"


def keep_manual_supports(result: Scene, current: Scene) -> Scene:
    """`result` (a fresh pipeline run) with every manual support of `current` kept.

    People may edit while a pipeline job runs. Their edges win; an automatic edge that would
    now close a cycle falls back to the structural supporter of its type.
    """
    ids = [o.id for o in result.objects]
    manual = [s for s in current.supports if s.source == "manual" and _within(s, ids)]
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


def _within(support: SupportRelation, ids: Sequence[str]) -> bool:
    """Whether the support's child and supporter are among these objects (or structural): a
    person's support of an object added by hand is not kept when a run lacks that object."""
    parent_ok = support.parent in ids or support.parent in STRUCTURAL_SUPPORTERS
    return support.child in ids and parent_ok
