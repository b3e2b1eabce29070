"""keep_people_objects: what a pipeline re-run keeps of the objects people set."""

from __future__ import annotations

from holiscene.pipeline.people import keep_people_objects, people_objects_changed_since
from holiscene_schema import SceneObject


def _obj(
    object_id: str, bbox: list[float], source: str, *person: str, cls: str = "chair"
) -> SceneObject:
    return SceneObject.model_validate(
        {
            "id": object_id,
            "class": cls,
            "bbox": bbox,
            "source": source,
            "set_by_person": list(person),
        }
    )


def test_a_detected_object_found_again_gives_way_to_the_persons_version() -> None:
    person = _obj("o0", [10, 10, 50, 50], "detector", "class", cls="sofa")
    found = [_obj("o0", [200, 10, 250, 60], "detector"), _obj("o1", [11, 9, 51, 50], "detector")]
    merged = keep_people_objects(found, [person])
    # The run's o1 is the person's o0 found again (IoU > 0.5); the run's own o0 is another
    # object and must not take the person's id.
    assert [(o.id, o.cls) for o in merged] == [("o0_1", "chair"), ("o0", "sofa")]
    assert merged[0].bbox == [200, 10, 250, 60]


def test_a_given_box_a_person_moved_is_not_found_again() -> None:
    person = _obj("o2", [300, 300, 350, 350], "given", "bbox")
    found = [_obj("o1", [0, 0, 20, 20], "given"), _obj("o2", [10, 10, 50, 50], "given")]
    merged = keep_people_objects(found, [person])
    assert [(o.id, o.bbox) for o in merged] == [
        ("o1", [0, 0, 20, 20]),
        ("o2", [300, 300, 350, 350]),
    ]


def test_objects_nobody_touched_are_the_runs() -> None:
    untouched = _obj("o0", [10, 10, 50, 50], "given")
    found = [_obj("o0", [12, 10, 50, 50], "given")]
    assert keep_people_objects(found, [untouched]) == found


def test_only_what_people_set_counts_as_changed_since_the_run() -> None:
    boxed = _obj("o0", [10, 10, 50, 50], "given", "bbox")
    recut = boxed.model_copy(update={"note": "placed"})  # the run's version: same box
    assert people_objects_changed_since([recut], [boxed]) == []
    moved = boxed.model_copy(update={"bbox": [12.0, 10.0, 50.0, 50.0]})
    assert people_objects_changed_since([recut], [moved]) == [moved]
    assert people_objects_changed_since([], [boxed]) == [boxed]
