"""The annotation workflow's rules, with no database and no HTTP: roles, which state change a
user may make, how uncertain a predicted scene is, and how far two annotations agree.

States: new -> predicted (the pipeline finished) -> in_annotation (an annotator took it) ->
submitted -> accepted | rejected (with a comment) ; rejected -> in_annotation (the annotator
fixes it) ; submitted -> in_annotation (its annotator takes it back before a reviewer
decides). A reviewer may ask for a second, independent annotation of a submitted or accepted
scene: its supports go back to the pipeline's guesses, the annotation round goes up and the
scene is predicted again, for someone who did not label it before.
"""

from __future__ import annotations

from collections.abc import Iterable
from dataclasses import dataclass

from holiscene_schema import (
    STRUCTURAL_CLASSES,
    Role,
    Scene,
    SceneObject,
    SceneState,
    SupportRelation,
    WorkflowAction,
)

from ..core.errors import DomainError

ROLE_RANK: dict[Role, int] = {"annotator": 1, "reviewer": 2, "admin": 3}
ROLES: tuple[Role, ...] = ("annotator", "reviewer", "admin")
STATES: tuple[SceneState, ...] = (
    "new",
    "predicted",
    "in_annotation",
    "submitted",
    "accepted",
    "rejected",
)
# The identity of every request in local single-user mode (loopback, no accounts yet).
LOCAL_USER = "local"
# Names the system writes as authors; no account may take them.
RESERVED_NAMES = frozenset({LOCAL_USER, "pipeline", "import", "system", "admin-cli"})
# A supporter the pipeline guessed without saying how sure it was counts as a coin toss.
UNKNOWN_CONFIDENCE = 0.5


def has_role(role: Role, needed: Role) -> bool:
    """Roles are nested: an admin may do what a reviewer may, a reviewer what an annotator may."""
    return ROLE_RANK[role] >= ROLE_RANK[needed]


class WorkflowError(DomainError):
    """A state change the workflow does not allow now (HTTP 409); the message says why."""

    status = 409


@dataclass(frozen=True)
class Actor:
    name: str
    role: Role
    local: bool = False  # the local single-user mode's user, who plays every part


@dataclass(frozen=True)
class SceneStatus:
    state: SceneState
    assignee: str | None
    annotation_round: int
    archived_by: str | None = None  # archived (by this admin): nobody edits it until restored


@dataclass(frozen=True)
class Transition:
    action: WorkflowAction
    to_state: SceneState
    assignee: str | None


def take_for_annotation(
    status: SceneStatus,
    actor: Actor,
    earlier_annotators: Iterable[str] = (),
    taking: bool = False,
) -> Transition | None:
    """What editing (or, with `taking`, taking) the scene does to its state; None when nothing
    changes.

    Raises WorkflowError when the actor may not work on the scene now. `earlier_annotators`:
    who submitted it in an earlier annotation round (a second annotation must be
    independent of the first).

    A submitted or accepted scene is locked for everyone, reviewers and admins included:
    what a reviewer judges, or accepted, is exactly what its annotator submitted. A reviewer
    who wants a change rejects the scene with a comment (its annotator fixes it; an admin
    may take it over), and an accepted scene changes only through a second annotation."""
    state, assignee = status.state, status.assignee
    check_not_archived(status)
    if state == "submitted":
        by = assignee or "someone"
        if has_role(actor.role, "reviewer") and actor.name != assignee:
            raise WorkflowError(
                f"the scene is submitted for review (by {by}): it stays as submitted while "
                "you judge it; to have something changed, send it back with a comment"
            )
        raise WorkflowError(
            f"the scene is submitted for review (by {by}): a reviewer must "
            "reject it before it can be edited"
        )
    if state == "accepted":
        raise WorkflowError(
            "the scene is accepted and can no longer be edited; a reviewer can ask for a "
            "second annotation"
        )
    if not actor.local and actor.name in set(earlier_annotators):
        raise WorkflowError(
            f"you annotated this scene in an earlier round; annotation round "
            f"{status.annotation_round} must come from someone else"
        )
    if state in ("new", "predicted"):
        return Transition("claim", "in_annotation", actor.name)
    admin = has_role(actor.role, "admin")
    if assignee not in (None, actor.name) and not (admin and taking):
        # Worded to start with "the scene": pages make the first letter a capital, and a
        # person's name is spelled as they chose it. An admin takes a scene over by taking it,
        # never by an edit: a stray click must not lock its annotator out unawares.
        take_over = ": take it over to edit it" if admin else ""
        if state == "rejected":
            hint = take_over or " (an admin can take it over)"
            raise WorkflowError(f"the scene was sent back to {assignee}, who fixes it{hint}")
        raise WorkflowError(f"the scene is being annotated by {assignee}{take_over}")
    if state == "rejected":
        return Transition("reopen", "in_annotation", actor.name)
    if assignee != actor.name:  # in annotation, unassigned or taken over by an admin
        return Transition("claim", "in_annotation", actor.name)
    return None


def edit_refusal(
    status: SceneStatus, actor: Actor, earlier_annotators: Iterable[str] = ()
) -> str | None:
    """Why the actor may not edit the scene now (supports, room layout), or None when they
    may: the rules of take_for_annotation, which every edit goes through."""
    try:
        take_for_annotation(status, actor, earlier_annotators)
    except WorkflowError as refused:
        return str(refused)
    return None


def release(status: SceneStatus, actor: Actor, predicted: bool, sent_back: bool) -> Transition:
    """Give back a scene taken by mistake: it waits for an annotator again, with its edits.
    `predicted`: the pipeline has run on it (else it is new again); `sent_back`: a reviewer
    rejected it in this annotation round, and then it stays with its annotator to fix."""
    if status.state != "in_annotation":
        raise WorkflowError(
            f"only a scene in annotation can be given back; this one is {describe(status.state)}"
        )
    if status.assignee not in (None, actor.name) and not has_role(actor.role, "admin"):
        raise WorkflowError(
            f"the scene is being annotated by {status.assignee}: only they or an admin can "
            "give it back"
        )
    if sent_back and not has_role(actor.role, "admin"):
        raise WorkflowError(
            "the scene was sent back by a reviewer to be fixed: fix it and submit it again "
            "(an admin can give it back)"
        )
    return Transition("release", "predicted" if predicted else "new", None)


def submit(status: SceneStatus, actor: Actor) -> Transition:
    if status.state != "in_annotation":
        raise WorkflowError(
            f"only a scene in annotation can be submitted; this one is {describe(status.state)}"
        )
    if status.assignee != actor.name:
        raise WorkflowError(
            f"only the annotator of this scene ({status.assignee or 'nobody yet'}) can submit it"
        )
    return Transition("submit", "submitted", actor.name)


def withdraw(status: SceneStatus, actor: Actor) -> Transition:
    """Take a submission back before a reviewer decides (submitted too soon, or a slip seen
    since): the scene is in annotation again, with its annotator."""
    if status.state != "submitted":
        raise WorkflowError(
            f"only a submitted scene can be taken back; this one is {describe(status.state)}"
        )
    if status.assignee != actor.name:
        raise WorkflowError(
            f"only the annotator who submitted this scene ({status.assignee or 'nobody'}) can "
            "take it back; a reviewer sends it back with a comment"
        )
    return Transition("withdraw", "in_annotation", actor.name)


def review(status: SceneStatus, actor: Actor, accept: bool) -> Transition:
    if status.state != "submitted":
        raise WorkflowError(
            f"only a submitted scene can be {'accepted' if accept else 'rejected'}; this one "
            f"is {describe(status.state)}"
        )
    if status.assignee == actor.name and not actor.local:
        raise WorkflowError("you submitted this scene: another reviewer must review it")
    if accept:
        return Transition("accept", "accepted", status.assignee)
    return Transition("reject", "rejected", status.assignee)


def second_annotation(status: SceneStatus) -> Transition:
    if status.state not in ("submitted", "accepted"):
        raise WorkflowError(
            "a second annotation can be asked for a submitted or accepted scene; this one is "
            f"{describe(status.state)}"
        )
    return Transition("second_annotation", "predicted", None)


def check_not_archived(status: SceneStatus) -> None:
    """WorkflowError for an archived scene: no edit, take, workflow step or job until an admin
    restores it."""
    if status.archived_by is not None:
        raise WorkflowError(
            f"the scene was archived by {status.archived_by}: an admin restores it before "
            "anyone works on it"
        )


def check_pipeline_allowed(status: SceneStatus) -> None:
    """Re-running the pipeline would change what a reviewer is judging or has accepted; an
    archived scene is left as it is."""
    check_not_archived(status)
    if status.state in ("submitted", "accepted"):
        raise WorkflowError(
            f"the scene is {describe(status.state)}: the pipeline cannot re-run on it now"
        )


def check_job_allowed(status: SceneStatus, actor: Actor) -> None:
    """Pipeline and placement jobs rewrite the scene's layout and placement, which would make
    its annotator's next save stale: on a scene someone holds, only they may start one, or an
    admin (who may take any scene over too)."""
    check_pipeline_allowed(status)
    holder = status.assignee
    if (
        status.state in ("in_annotation", "rejected")
        and holder not in (None, actor.name)
        and not has_role(actor.role, "admin")
    ):
        raise WorkflowError(
            f"{holder} is annotating this scene: only they (or an admin) can run the pipeline "
            "or re-place objects on it"
        )


def describe(state: SceneState) -> str:
    return state.replace("_", " ")


def _needing_supporter(scene: Scene) -> list[SceneObject]:
    return [o for o in scene.objects if o.cls not in STRUCTURAL_CLASSES]


def scene_uncertainty(scene: Scene) -> float:
    """Mean over the objects that need a supporter of how unsure they are (`_object_doubt`),
    raised by each stage that warned (WARNING_DOUBT apiece: masks left as boxes, heights out
    of range...): the Relation Network is often sure of itself where the scene is not.
    1 for a scene with no such objects: nothing in it is known yet (its objects are still to
    be found), so it comes first for annotation."""
    objects = _needing_supporter(scene)
    if not objects:
        return 1.0
    supports = {s.child: s for s in scene.supports}
    mean = sum(_object_doubt(o, supports.get(o.id)) for o in objects) / len(objects)
    warnings = sum(1 for stage in scene.stages if stage.warning)
    return round(1.0 - (1.0 - mean) * (1.0 - WARNING_DOUBT) ** warnings, 6)


# How much a stage's warning adds to a scene's doubt, as a share of what is still trusted.
WARNING_DOUBT = 0.1


def _object_doubt(obj: SceneObject, support: SupportRelation | None) -> float:
    """How unsure the scene is of one object: of its supporter, 1 - confidence for the
    pipeline's guess (0.5 when it gave none), 1 without a supporter, 0 when a person set it;
    and of the object itself when the detector made it and no person has touched it since:
    then the supporter only counts if the object is real, whose chance is its score."""
    if support is None:
        doubt = 1.0
    elif support.source == "auto":
        confidence = support.confidence
        doubt = 1.0 - (UNKNOWN_CONFIDENCE if confidence is None else confidence)
    else:
        return 0.0
    if obj.source == "detector" and not obj.set_by_person:
        real = UNKNOWN_CONFIDENCE if obj.score is None else obj.score
        doubt = 1.0 - (1.0 - doubt) * real
    return doubt


@dataclass(frozen=True)
class Agreement:
    objects: int
    matching: int

    @property
    def share(self) -> float:
        return self.matching / self.objects if self.objects else 0.0


def support_agreement(first: Scene, second: Scene) -> Agreement:
    """Share of the objects (that need a supporter, in either scene) whose (supporter, type)
    is the same in both annotations; an object without a supporter in both counts as a match."""
    ids = list(dict.fromkeys(o.id for o in _needing_supporter(first) + _needing_supporter(second)))
    a = {s.child: (s.parent, s.type) for s in first.supports}
    b = {s.child: (s.parent, s.type) for s in second.supports}
    matching = sum(1 for object_id in ids if a.get(object_id) == b.get(object_id))
    return Agreement(objects=len(ids), matching=matching)


def pipeline_supports_only(scene: Scene, pipeline_scene: Scene) -> Scene:
    """`scene` with the supports of the pipeline's revision that the pipeline guessed (source
    auto), for an independent second annotation. Objects a person labelled before that run
    are left without a supporter: the pipeline's own guess for them was not kept."""
    ids = {o.id for o in scene.objects}
    auto = [s for s in pipeline_scene.supports if s.source == "auto" and s.child in ids]
    return scene.model_copy(update={"supports": auto})
