"""What a pipeline re-run keeps of people's work on objects: every object a person added or
changed (class, box or mask: `SceneObject.set_by_person`) stays as they left it, and the run's
objects that are the same object found again give way to it. People's supports are kept by
editing.keep_manual_supports when the run is stored."""

from __future__ import annotations

from collections.abc import Sequence

from holiscene_schema import RemovedObject, SceneObject

from ..evaluation.box_iou import iou_2d

# A run's object overlapping an object a person set this much is the same object found again.
SAME_OBJECT_IOU = 0.5


def keep_people_objects(
    found: Sequence[SceneObject],
    kept: Sequence[SceneObject],
    removed: Sequence[RemovedObject] = (),
) -> list[SceneObject]:
    """A pipeline run's objects with the objects people set (`kept`: any `set_by_person`) kept
    as they left them. A run's object is dropped as the same object found again when it
    overlaps a kept one (IoU at least SAME_OBJECT_IOU), or when it is a given box with a kept
    object's id (given ids are stable; a person may have moved that box far). A run's object
    whose id a kept object holds gets a fresh one. The objects people `removed` stay out the
    same way (a given box by its id, any other by overlap)."""
    people = [_without_placement(o) for o in kept if o.set_by_person]
    people_ids = {o.id for o in people}

    removed_ids = {r.id for r in removed}
    taken_boxes = [o.bbox for o in people] + [r.bbox for r in removed]

    def found_again(obj: SceneObject) -> bool:
        if obj.source == "given" and obj.id in people_ids | removed_ids:
            return True
        return any(iou_2d(obj.bbox, box) >= SAME_OBJECT_IOU for box in taken_boxes)

    by_id = {o.id: o for o in people}
    taken = people_ids | {o.id for o in found}
    merged: list[SceneObject] = []
    for obj in found:
        if found_again(obj):
            # The person's version takes the place of the object it was found as.
            if obj.id in by_id:
                merged.append(by_id.pop(obj.id))
            continue
        if obj.id in people_ids:
            fresh = _fresh_id(obj.id, taken)
            taken.add(fresh)
            obj = obj.model_copy(update={"id": fresh})
        merged.append(obj)
    return [*merged, *by_id.values()]


def _without_placement(obj: SceneObject) -> SceneObject:
    """What a run computes again for a kept object (3D box, corners, shape, notes) cleared."""
    return obj.model_copy(update={"box_3d": None, "corners_3d": None, "mesh": None, "note": None})


def _fresh_id(base: str, taken: set[str]) -> str:
    number = 1
    while f"{base}_{number}" in taken:
        number += 1
    return f"{base}_{number}"


def people_objects_changed_since(
    result: Sequence[SceneObject], current: Sequence[SceneObject]
) -> list[SceneObject]:
    """The objects people set in `current` that a run's `result` does not have as they are
    now (set while the run worked): keep_people_objects keeps them when the run is stored."""
    ran = {o.id: o for o in result}
    return [o for o in current if o.set_by_person and not _same_people_parts(o, ran.get(o.id))]


def _same_people_parts(person: SceneObject, found: SceneObject | None) -> bool:
    """Whether `found` has what a person set on `person` (the run may have cut a new mask for
    an object whose box, not mask, a person set)."""
    if found is None or found.set_by_person != person.set_by_person:
        return False
    parts = set(person.set_by_person)
    return (
        ("class" not in parts or found.cls == person.cls)
        and (not parts & {"bbox", "object"} or found.bbox == person.bbox)
        and ("mask" not in parts or found.mask == person.mask)
        and ("object" not in parts or found.cls == person.cls)
    )
