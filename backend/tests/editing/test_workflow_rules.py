"""The workflow's rules without a database: uncertainty, agreement, who may do what."""

from __future__ import annotations

import pytest
from holiscene.editing.workflow_rules import (
    WARNING_DOUBT,
    Actor,
    SceneStatus,
    WorkflowError,
    has_role,
    release,
    review,
    scene_uncertainty,
    submit,
    support_agreement,
    take_for_annotation,
    withdraw,
)
from holiscene_schema import StageRun

from ..stored_scenes import PREDICTED, make_scene

ANN = Actor("ann", "annotator")
BOB = Actor("bob", "annotator")
REV = Actor("rita", "reviewer")
ADMIN = Actor("ada", "admin")


def test_roles_are_nested() -> None:
    assert has_role("admin", "reviewer") and has_role("admin", "annotator")
    assert has_role("reviewer", "annotator") and not has_role("reviewer", "admin")
    assert not has_role("annotator", "reviewer")


def test_uncertainty_is_the_mean_doubt_over_objects_that_need_a_supporter() -> None:
    # o0: 1 - 0.9, o1: 1 - 0.3, o2: no confidence (0.5), o3: no supporter (1); the wall
    # needs none and does not count.
    scene = make_scene(PREDICTED[:3], {"o0": 0.9, "o1": 0.3, "o2": None})
    assert scene_uncertainty(scene) == pytest.approx((0.1 + 0.7 + 0.5 + 1.0) / 4)
    # A person's supporter is certain.
    manual = scene.model_copy(
        update={"supports": [s.model_copy(update={"source": "manual"}) for s in scene.supports]}
    )
    assert scene_uncertainty(manual) == pytest.approx(1.0 / 4)


def test_an_object_only_the_detector_vouches_for_is_doubtful_by_its_score() -> None:
    scene = make_scene(PREDICTED[:3], {"o0": 0.9, "o1": 0.3, "o2": None})
    given = scene_uncertainty(scene)
    detected = scene.model_copy(
        update={
            "objects": [
                o.model_copy(update={"source": "detector", "score": 0.4}) if o.id == "o0" else o
                for o in scene.objects
            ]
        }
    )
    # o0: real with chance 0.4, its supporter right with 0.9: doubt 1 - 0.4 * 0.9.
    assert scene_uncertainty(detected) == pytest.approx((1 - 0.36 + 0.7 + 0.5 + 1.0) / 4)
    assert scene_uncertainty(detected) > given
    # Once a person touched it (accepted it, fixed its class...), its supporter's doubt alone.
    touched = detected.model_copy(
        update={
            "objects": [
                o.model_copy(update={"set_by_person": ["class"]}) if o.id == "o0" else o
                for o in detected.objects
            ]
        }
    )
    assert scene_uncertainty(touched) == pytest.approx(given)
    # A person's supporter settles it too.
    settled = detected.model_copy(
        update={
            "supports": [
                s.model_copy(update={"source": "manual"}) if s.child == "o0" else s
                for s in detected.supports
            ]
        }
    )
    assert scene_uncertainty(settled) == pytest.approx((0.7 + 0.5 + 1.0) / 4)


def test_each_stage_warning_raises_the_doubt_of_a_scene_its_supports_are_sure_of() -> None:
    sure = make_scene(PREDICTED, {"o0": 1.0, "o1": 1.0, "o2": 1.0, "o3": 1.0})
    assert scene_uncertainty(sure) == 0.0
    stages = [
        StageRun(name="masks_grabcut", seconds=0.1, note="2 boxes left", warning=True),
        StageRun(name="placement", seconds=0.1, note="placed", warning=False),
        StageRun(name="heights_by_metrology", seconds=0.1, note="1 height", warning=True),
    ]
    warned = sure.model_copy(update={"stages": stages})
    assert scene_uncertainty(warned) == pytest.approx(1 - (1 - WARNING_DOUBT) ** 2)
    # On top of the supports' doubt, as a share of what is still trusted.
    unsure = make_scene(PREDICTED[:3], {"o0": 0.9, "o1": 0.3, "o2": None})
    mean = (0.1 + 0.7 + 0.5 + 1.0) / 4
    both = unsure.model_copy(update={"stages": stages[:1]})
    assert scene_uncertainty(both) == pytest.approx(1 - (1 - mean) * (1 - WARNING_DOUBT))


def test_a_scene_without_objects_to_support_is_the_most_uncertain() -> None:
    scene = make_scene([])
    assert scene_uncertainty(scene.model_copy(update={"objects": []})) == 1.0
    walls_only = [o for o in scene.objects if o.cls == "wall"]
    assert scene_uncertainty(scene.model_copy(update={"objects": walls_only})) == 1.0


def test_agreement_on_a_hand_made_pair() -> None:
    first = make_scene(PREDICTED)
    # o1 on the floor instead of the table (supporter differs), o2 behind instead of below
    # (type differs), o0 and o3 the same.
    second = make_scene(
        [
            ("o0", "floor", "below"),
            ("o1", "floor", "below"),
            ("o2", "o0", "behind"),
            ("o3", "floor", "below"),
        ]
    )
    result = support_agreement(first, second)
    assert (result.objects, result.matching, result.share) == (4, 2, 0.5)
    assert support_agreement(first, first).share == 1.0
    # An object without a supporter in both annotations agrees; in one only, it does not.
    assert support_agreement(make_scene(PREDICTED[:3]), make_scene(PREDICTED[:3])).share == 1.0
    assert support_agreement(make_scene(PREDICTED[:3]), first).matching == 3


def test_taking_a_scene() -> None:
    predicted = SceneStatus("predicted", None, 1)
    taken = take_for_annotation(predicted, ANN)
    assert taken is not None and (taken.action, taken.to_state, taken.assignee) == (
        "claim",
        "in_annotation",
        "ann",
    )
    mine = SceneStatus("in_annotation", "ann", 1)
    assert take_for_annotation(mine, ANN) is None  # editing on: nothing changes
    with pytest.raises(WorkflowError, match="being annotated by ann"):
        take_for_annotation(mine, BOB)
    with pytest.raises(WorkflowError, match="being annotated by ann"):
        take_for_annotation(mine, REV)
    # An admin takes a scene over by taking it, not by an edit.
    with pytest.raises(WorkflowError, match="being annotated by ann: take it over to edit it"):
        take_for_annotation(mine, ADMIN)
    admin_takes = take_for_annotation(mine, ADMIN, taking=True)
    assert admin_takes is not None and admin_takes.assignee == "ada"
    with pytest.raises(WorkflowError, match="sent back to ann, who fixes it: take it over"):
        take_for_annotation(SceneStatus("rejected", "ann", 1), ADMIN)
    rejected = take_for_annotation(SceneStatus("rejected", "ann", 1), ANN)
    assert rejected is not None and (rejected.action, rejected.to_state) == (
        "reopen",
        "in_annotation",
    )
    for state in ("submitted", "accepted"):
        with pytest.raises(WorkflowError):
            take_for_annotation(SceneStatus(state, "ann", 1), ANN)  # type: ignore[arg-type]
    # Round 2 must be someone else's.
    with pytest.raises(WorkflowError, match="earlier round"):
        take_for_annotation(SceneStatus("predicted", None, 2), ANN, {"ann"})
    assert take_for_annotation(SceneStatus("predicted", None, 2), BOB, {"ann"}) is not None


def test_submitting_and_reviewing() -> None:
    mine = SceneStatus("in_annotation", "ann", 1)
    assert submit(mine, ANN).to_state == "submitted"
    with pytest.raises(WorkflowError, match=r"only the annotator of this scene \(ann\)"):
        submit(mine, BOB)
    with pytest.raises(WorkflowError, match="only a scene in annotation"):
        submit(SceneStatus("predicted", None, 1), ANN)
    submitted = SceneStatus("submitted", "ann", 1)
    assert review(submitted, REV, accept=True).to_state == "accepted"
    rejected = review(submitted, REV, accept=False)
    assert (rejected.to_state, rejected.assignee) == ("rejected", "ann")
    with pytest.raises(WorkflowError, match="only a submitted scene"):
        review(mine, REV, accept=True)
    with pytest.raises(WorkflowError, match="another reviewer"):
        review(SceneStatus("submitted", "rita", 1), REV, accept=True)
    # The local single-user mode plays every part.
    local = Actor("local", "admin", local=True)
    assert review(SceneStatus("submitted", "local", 1), local, accept=True).to_state == "accepted"


def test_a_submission_is_taken_back_by_its_annotator_before_a_review() -> None:
    submitted = SceneStatus("submitted", "ann", 1)
    back = withdraw(submitted, ANN)
    assert (back.action, back.to_state, back.assignee) == ("withdraw", "in_annotation", "ann")
    with pytest.raises(WorkflowError, match=r"only the annotator who submitted this scene \(ann\)"):
        withdraw(submitted, BOB)
    with pytest.raises(WorkflowError, match="a reviewer sends it back"):
        withdraw(submitted, REV)
    for state in ("in_annotation", "accepted", "rejected"):
        with pytest.raises(WorkflowError, match="only a submitted scene can be taken back"):
            withdraw(SceneStatus(state, "ann", 1), ANN)


def test_release_gives_a_scene_back_as_new_or_predicted_unless_sent_back_to_be_fixed() -> None:
    taken = SceneStatus("in_annotation", "ann", 1)
    assert release(taken, ANN, predicted=True, sent_back=False).to_state == "predicted"
    back = release(taken, ANN, predicted=False, sent_back=False)
    assert (back.action, back.to_state, back.assignee) == ("release", "new", None)
    with pytest.raises(WorkflowError, match="only they or an admin"):
        release(taken, BOB, predicted=True, sent_back=False)
    with pytest.raises(WorkflowError, match="sent back by a reviewer"):
        release(taken, ANN, predicted=True, sent_back=True)
    assert release(taken, ADMIN, predicted=True, sent_back=True).to_state == "predicted"
    with pytest.raises(WorkflowError, match="only a scene in annotation"):
        release(SceneStatus("submitted", "ann", 1), ANN, predicted=True, sent_back=False)
